//! Compute and dynamic-rendering graphics pipelines. Layouts come from the bindings a pass
//! declares, checked against what naga reflected from the shaders.

use super::context::{Context, Garbage};
use super::descriptor_counts::{descriptor_type, DescriptorCounts};
use crate::error::{Error, Result, VkContext};
use crate::shaders::{ReflectedBinding, ShaderModuleInfo};
use ash::vk;
use std::sync::Arc;

/// Stages every descriptor set layout is visible to. One value for all layouts keeps identically
/// declared sets (the per-frame set 0) compatible across pipelines.
pub const ALL_STAGES: vk::ShaderStageFlags = vk::ShaderStageFlags::from_raw(
    vk::ShaderStageFlags::VERTEX.as_raw()
        | vk::ShaderStageFlags::FRAGMENT.as_raw()
        | vk::ShaderStageFlags::COMPUTE.as_raw(),
);

/// The union of the modules' reflected bindings, sorted.
pub fn reflected_union(modules: &[&ShaderModuleInfo]) -> Vec<ReflectedBinding> {
    let mut all: Vec<ReflectedBinding> = modules
        .iter()
        .flat_map(|m| m.bindings.iter().copied())
        .collect();
    all.sort();
    all.dedup();
    all
}

/// Error unless the pass's declaration equals the shaders' reflection.
pub fn check_bindings(
    pass: &str,
    modules: &[&ShaderModuleInfo],
    declared: &[ReflectedBinding],
) -> Result<()> {
    let reflected = reflected_union(modules);
    let mut declared = declared.to_vec();
    declared.sort();
    if reflected != declared {
        let names: Vec<String> = modules.iter().map(|m| m.label()).collect();
        return Err(Error::Reflection(format!(
            "pass '{pass}' declares {declared:?} but {} reflect {reflected:?}",
            names.join(" + ")
        )));
    }
    Ok(())
}

fn create_set_layouts(
    ctx: &Context,
    declared: &[ReflectedBinding],
) -> Result<Vec<vk::DescriptorSetLayout>> {
    let max_set = declared.iter().map(|b| b.set + 1).max().unwrap_or(0);
    let mut layouts = Vec::new();
    for set in 0..max_set {
        let bindings: Vec<_> = declared
            .iter()
            .filter(|b| b.set == set)
            .map(|b| {
                vk::DescriptorSetLayoutBinding::default()
                    .binding(b.binding)
                    .descriptor_type(descriptor_type(b.kind))
                    .descriptor_count(b.count)
                    .stage_flags(ALL_STAGES)
            })
            .collect();
        let info = vk::DescriptorSetLayoutCreateInfo::default().bindings(&bindings);
        // SAFETY: valid create info; destroyed through the deletion queue.
        match unsafe { ctx.device.create_descriptor_set_layout(&info, None) }
            .vk("vkCreateDescriptorSetLayout")
        {
            Ok(l) => {
                let counts = DescriptorCounts::of(declared.iter().filter(|b| b.set == set));
                ctx.layout_counts
                    .lock()
                    .unwrap_or_else(|e| e.into_inner())
                    .insert(l, counts);
                layouts.push(l)
            }
            Err(e) => {
                for l in layouts {
                    ctx.defer(Garbage::DescriptorSetLayout(l));
                }
                return Err(e);
            }
        }
    }
    Ok(layouts)
}

fn shader_module(ctx: &Context, info: &ShaderModuleInfo) -> Result<vk::ShaderModule> {
    let words = ash::util::read_spv(&mut std::io::Cursor::new(info.spirv))
        .map_err(|e| Error::Reflection(format!("{}: bad SPIR-V: {e}", info.label())))?;
    let create = vk::ShaderModuleCreateInfo::default().code(&words);
    // SAFETY: SPIR-V validated by naga at build time; the module is destroyed after pipeline
    // creation by the caller.
    unsafe { ctx.device.create_shader_module(&create, None) }.vk("vkCreateShaderModule")
}

/// A pipeline with its layout and descriptor set layouts (index = set number).
pub struct Pipeline {
    ctx: Arc<Context>,
    pub raw: vk::Pipeline,
    pub layout: vk::PipelineLayout,
    pub set_layouts: Vec<vk::DescriptorSetLayout>,
    pub bind_point: vk::PipelineBindPoint,
    pub push_stages: vk::ShaderStageFlags,
    pub workgroup_size: [u32; 3],
    pub name: &'static str,
}

impl Drop for Pipeline {
    fn drop(&mut self) {
        self.ctx.defer(Garbage::Pipeline(self.raw));
        self.ctx.defer(Garbage::PipelineLayout(self.layout));
        for l in self.set_layouts.drain(..) {
            self.ctx.defer(Garbage::DescriptorSetLayout(l));
        }
    }
}

fn layout_for(
    ctx: &Arc<Context>,
    name: &'static str,
    modules: &[&ShaderModuleInfo],
    declared: &[ReflectedBinding],
) -> Result<(
    Vec<vk::DescriptorSetLayout>,
    vk::PipelineLayout,
    vk::ShaderStageFlags,
)> {
    check_bindings(name, modules, declared)?;
    let push_bytes = modules
        .iter()
        .map(|m| m.push_constant_bytes)
        .max()
        .unwrap_or(0);
    if push_bytes > ctx.info.max_push_constants_size {
        return Err(Error::MissingFeature(format!(
            "{push_bytes} bytes of push constants for '{name}' (limit {})",
            ctx.info.max_push_constants_size
        )));
    }
    let mut push_stages = vk::ShaderStageFlags::empty();
    for m in modules.iter().filter(|m| m.push_constant_bytes > 0) {
        push_stages |= match m.stage {
            crate::shaders::ShaderStage::Vertex => vk::ShaderStageFlags::VERTEX,
            crate::shaders::ShaderStage::Fragment => vk::ShaderStageFlags::FRAGMENT,
            crate::shaders::ShaderStage::Compute => vk::ShaderStageFlags::COMPUTE,
        };
    }
    let set_layouts = create_set_layouts(ctx, declared)?;
    let ranges = [vk::PushConstantRange {
        stage_flags: push_stages,
        offset: 0,
        size: push_bytes,
    }];
    let mut info = vk::PipelineLayoutCreateInfo::default().set_layouts(&set_layouts);
    if push_bytes > 0 {
        info = info.push_constant_ranges(&ranges);
    }
    // SAFETY: set layouts are live; destroyed through the deletion queue.
    let layout = match unsafe { ctx.device.create_pipeline_layout(&info, None) }
        .vk("vkCreatePipelineLayout")
    {
        Ok(l) => l,
        Err(e) => {
            for l in set_layouts {
                ctx.defer(Garbage::DescriptorSetLayout(l));
            }
            return Err(e);
        }
    };
    Ok((set_layouts, layout, push_stages))
}

impl Pipeline {
    pub fn compute(
        ctx: &Arc<Context>,
        name: &'static str,
        module: &ShaderModuleInfo,
        declared: &[ReflectedBinding],
    ) -> Result<Self> {
        Self::compute_specialized(ctx, name, module, declared, &[])
    }

    /// A compute pipeline whose specialization constants `constant_id = i` take `constants[i]`
    /// (32-bit each), so the driver compiles branches on them away.
    pub fn compute_specialized(
        ctx: &Arc<Context>,
        name: &'static str,
        module: &ShaderModuleInfo,
        declared: &[ReflectedBinding],
        constants: &[u32],
    ) -> Result<Self> {
        let (set_layouts, layout, push_stages) = layout_for(ctx, name, &[module], declared)?;
        let mut pipeline = Pipeline {
            ctx: ctx.clone(),
            raw: vk::Pipeline::null(),
            layout,
            set_layouts,
            bind_point: vk::PipelineBindPoint::COMPUTE,
            push_stages,
            workgroup_size: module.workgroup_size,
            name,
        };
        let sm = shader_module(ctx, module)?;
        let entries: Vec<vk::SpecializationMapEntry> = (0..constants.len() as u32)
            .map(|i| vk::SpecializationMapEntry {
                constant_id: i,
                offset: 4 * i,
                size: 4,
            })
            .collect();
        let data: Vec<u8> = constants.iter().flat_map(|c| c.to_le_bytes()).collect();
        let specialization = vk::SpecializationInfo::default()
            .map_entries(&entries)
            .data(&data);
        let mut stage = vk::PipelineShaderStageCreateInfo::default()
            .stage(vk::ShaderStageFlags::COMPUTE)
            .module(sm)
            .name(c"main");
        if !constants.is_empty() {
            stage = stage.specialization_info(&specialization);
        }
        let info = [vk::ComputePipelineCreateInfo::default()
            .stage(stage)
            .layout(layout)];
        // SAFETY: module and layout are live; the module is destroyed right after.
        let result = unsafe {
            let r = ctx
                .device
                .create_compute_pipelines(vk::PipelineCache::null(), &info, None);
            ctx.device.destroy_shader_module(sm, None);
            r
        };
        pipeline.raw = result.map_err(|(_, e)| e).vk("vkCreateComputePipelines")?[0];
        pipeline.name_objects(module);
        Ok(pipeline)
    }

    pub fn graphics(
        ctx: &Arc<Context>,
        name: &'static str,
        desc: &GraphicsDesc<'_>,
        declared: &[ReflectedBinding],
    ) -> Result<Self> {
        let modules = [desc.vertex, desc.fragment];
        let (set_layouts, layout, push_stages) = layout_for(ctx, name, &modules, declared)?;
        let mut pipeline = Pipeline {
            ctx: ctx.clone(),
            raw: vk::Pipeline::null(),
            layout,
            set_layouts,
            bind_point: vk::PipelineBindPoint::GRAPHICS,
            push_stages,
            workgroup_size: [0; 3],
            name,
        };
        let vs = shader_module(ctx, desc.vertex)?;
        let fs = match shader_module(ctx, desc.fragment) {
            Ok(fs) => fs,
            Err(e) => {
                // SAFETY: `vs` is unused.
                unsafe { ctx.device.destroy_shader_module(vs, None) };
                return Err(e);
            }
        };
        let stages = [
            vk::PipelineShaderStageCreateInfo::default()
                .stage(vk::ShaderStageFlags::VERTEX)
                .module(vs)
                .name(c"main"),
            vk::PipelineShaderStageCreateInfo::default()
                .stage(vk::ShaderStageFlags::FRAGMENT)
                .module(fs)
                .name(c"main"),
        ];
        let vertex_input = vk::PipelineVertexInputStateCreateInfo::default()
            .vertex_binding_descriptions(desc.vertex_bindings)
            .vertex_attribute_descriptions(desc.vertex_attributes);
        let input_assembly = vk::PipelineInputAssemblyStateCreateInfo::default()
            .topology(vk::PrimitiveTopology::TRIANGLE_LIST);
        let viewport = vk::PipelineViewportStateCreateInfo::default()
            .viewport_count(1)
            .scissor_count(1);
        let raster = vk::PipelineRasterizationStateCreateInfo::default()
            .polygon_mode(vk::PolygonMode::FILL)
            .cull_mode(vk::CullModeFlags::NONE)
            .front_face(vk::FrontFace::COUNTER_CLOCKWISE)
            .line_width(1.0);
        let multisample = vk::PipelineMultisampleStateCreateInfo::default()
            .rasterization_samples(vk::SampleCountFlags::TYPE_1);
        let depth_test = desc.depth_format != vk::Format::UNDEFINED;
        let depth = vk::PipelineDepthStencilStateCreateInfo::default()
            .depth_test_enable(depth_test)
            .depth_write_enable(depth_test)
            .depth_compare_op(vk::CompareOp::LESS);
        let blend_attachments: Vec<_> = desc
            .color_formats
            .iter()
            .map(|_| {
                let state = vk::PipelineColorBlendAttachmentState::default()
                    .color_write_mask(vk::ColorComponentFlags::RGBA);
                match desc.blend {
                    Blend::Replace => state,
                    // out = src + (1 - src.a) * dst, colour and alpha alike.
                    Blend::Premultiplied => state
                        .blend_enable(true)
                        .src_color_blend_factor(vk::BlendFactor::ONE)
                        .dst_color_blend_factor(vk::BlendFactor::ONE_MINUS_SRC_ALPHA)
                        .color_blend_op(vk::BlendOp::ADD)
                        .src_alpha_blend_factor(vk::BlendFactor::ONE)
                        .dst_alpha_blend_factor(vk::BlendFactor::ONE_MINUS_SRC_ALPHA)
                        .alpha_blend_op(vk::BlendOp::ADD),
                }
            })
            .collect();
        let blend =
            vk::PipelineColorBlendStateCreateInfo::default().attachments(&blend_attachments);
        let dynamic_states = [vk::DynamicState::VIEWPORT, vk::DynamicState::SCISSOR];
        let dynamic = vk::PipelineDynamicStateCreateInfo::default().dynamic_states(&dynamic_states);
        let mut rendering = vk::PipelineRenderingCreateInfo::default()
            .color_attachment_formats(desc.color_formats)
            .depth_attachment_format(desc.depth_format);
        let info = [vk::GraphicsPipelineCreateInfo::default()
            .stages(&stages)
            .vertex_input_state(&vertex_input)
            .input_assembly_state(&input_assembly)
            .viewport_state(&viewport)
            .rasterization_state(&raster)
            .multisample_state(&multisample)
            .depth_stencil_state(&depth)
            .color_blend_state(&blend)
            .dynamic_state(&dynamic)
            .layout(layout)
            .push_next(&mut rendering)];
        // SAFETY: all state structs are locals alive for the call; the modules are destroyed
        // right after creation.
        let result = unsafe {
            let r = ctx
                .device
                .create_graphics_pipelines(vk::PipelineCache::null(), &info, None);
            ctx.device.destroy_shader_module(vs, None);
            ctx.device.destroy_shader_module(fs, None);
            r
        };
        pipeline.raw = result.map_err(|(_, e)| e).vk("vkCreateGraphicsPipelines")?[0];
        pipeline.name_objects(desc.fragment);
        Ok(pipeline)
    }

    /// Debug names: the pipeline and its layout carry the pass name and the shader it runs.
    fn name_objects(&self, module: &ShaderModuleInfo) {
        let name = format!("{} ({})", self.name, module.label());
        self.ctx.names.set(self.raw, &name);
        self.ctx.names.set(self.layout, &name);
        for (i, l) in self.set_layouts.iter().enumerate() {
            self.ctx.names.set(*l, &format!("{name} set {i}"));
        }
    }
}

/// How a graphics pipeline writes its colour attachments.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Blend {
    /// The fragment replaces the attachment (the raster passes).
    Replace,
    /// Premultiplied-alpha "over" (the viewer's overlay: egui's colours are premultiplied).
    Premultiplied,
}

/// Fixed-function description of a raster pass (dynamic rendering, depth test LESS unless
/// `depth_format` is UNDEFINED, no culling: OBJ winding is not trusted).
pub struct GraphicsDesc<'a> {
    pub vertex: &'a ShaderModuleInfo,
    pub fragment: &'a ShaderModuleInfo,
    pub vertex_bindings: &'a [vk::VertexInputBindingDescription],
    pub vertex_attributes: &'a [vk::VertexInputAttributeDescription],
    pub color_formats: &'a [vk::Format],
    /// UNDEFINED: no depth attachment and no depth test.
    pub depth_format: vk::Format,
    pub blend: Blend,
}
