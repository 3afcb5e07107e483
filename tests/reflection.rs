//! Every pass's declared descriptor layout equals what naga reflected from its shaders, and
//! every compiled shader module belongs to some pass.

mod common;

use ssgi::renderer::{all_layouts, all_passes};
use ssgi::shaders::{DescriptorKind, ReflectedBinding, ALL};
use ssgi::vk::pipeline::check_bindings;

/// The renderer's pipelines and the viewer overlay's.
fn every_layout() -> Vec<ssgi::passes::layout::PassLayout> {
    let mut v = all_layouts();
    v.push(ssgi::frontend::overlay::layout());
    v
}

#[test]
fn every_pass_layout_matches_reflection() {
    for layout in every_layout() {
        check_bindings(layout.pass.name(), &layout.modules, &layout.declared)
            .unwrap_or_else(|e| panic!("{e}"));
    }
}

#[test]
fn every_shader_module_is_used_by_a_pass() {
    let layouts = every_layout();
    for module in ALL {
        let used = layouts
            .iter()
            .any(|l| l.modules.iter().any(|m| std::ptr::eq(*m, *module)));
        assert!(used, "{} is compiled but no pass uses it", module.label());
    }
}

/// A pass is known by its name (timing rows, skip reports, labels): no two passes share one,
/// and every pipeline's pass is in the recording order.
#[test]
fn pass_names_are_unique_and_every_pass_is_ordered() {
    let all = all_passes();
    for (i, p) in all.iter().enumerate() {
        assert!(
            !all[..i].iter().any(|q| q.name() == p.name()),
            "two passes are named {}",
            p.name()
        );
    }
    for layout in all_layouts() {
        assert!(
            all.contains(&layout.pass),
            "{} has a pipeline but no place in renderer::all_passes",
            layout.pass.name()
        );
    }
}

/// An effect is known by its name (state readback, reports): no two registered effects share
/// one.
#[test]
fn effect_names_are_unique() {
    let names: Vec<&str> = ssgi::effects::REGISTRY
        .iter()
        .map(|r| r.id.name())
        .collect();
    for (i, n) in names.iter().enumerate() {
        assert!(!names[..i].contains(n), "two effects are named {n}");
    }
}

#[test]
fn a_wrong_declaration_is_rejected() {
    let layout = all_layouts()
        .into_iter()
        .find(|l| l.pass == ssgi::effects::direct::pass::DIRECT)
        .unwrap();
    let mut wrong: Vec<ReflectedBinding> = layout.declared.to_vec();
    wrong.last_mut().unwrap().kind = DescriptorKind::SampledImage;
    let err = check_bindings(layout.pass.name(), &layout.modules, &wrong).unwrap_err();
    assert!(err.to_string().contains("direct"), "{err}");
    let missing = &layout.declared[..layout.declared.len() - 1];
    assert!(check_bindings(layout.pass.name(), &layout.modules, missing).is_err());
}

#[test]
fn compute_modules_have_workgroups_and_graphics_do_not() {
    for m in ALL {
        let wg: u32 = m.workgroup_size.iter().product();
        match m.stage {
            ssgi::shaders::ShaderStage::Compute => assert!(wg > 0, "{}", m.label()),
            _ => assert_eq!(wg, 0, "{}", m.label()),
        }
        assert_eq!(m.spirv.len() % 4, 0);
        assert_eq!(
            &m.spirv[..4],
            &0x0723_0203u32.to_le_bytes(),
            "{} SPIR-V magic",
            m.label()
        );
    }
}

// ------------------------------------------------------------- shared blocks (build.rs)

#[path = "../build/block_layout.rs"]
#[allow(dead_code)]
mod block_layout;

use ssgi::shaders::{
    AoParams, BlockMember, CcipcaPush, CountersHeader, EffectPush, FrameBlock, GBufferResolvePush,
    ImageStatsPush, MaterialPush, OverlayPush, ProbePush, ReprojectPush, SraaPush, SsdoParams,
    SvgfPush, VplParams, PROBES,
};

/// The generated struct of a GLSL block: its members and size.
fn generated(name: &str) -> (&'static [BlockMember], usize) {
    match name {
        "Frame" => (FrameBlock::MEMBERS, FrameBlock::SIZE),
        "Effect" => (EffectPush::MEMBERS, EffectPush::SIZE),
        "Ccipca" => (CcipcaPush::MEMBERS, CcipcaPush::SIZE),
        "Svgf" => (SvgfPush::MEMBERS, SvgfPush::SIZE),
        "Ssdo" => (SsdoParams::MEMBERS, SsdoParams::SIZE),
        "Ao" => (AoParams::MEMBERS, AoParams::SIZE),
        "Sraa" => (SraaPush::MEMBERS, SraaPush::SIZE),
        "Vpl" => (VplParams::MEMBERS, VplParams::SIZE),
        "Counters" => (CountersHeader::MEMBERS, CountersHeader::SIZE),
        "Material" => (MaterialPush::MEMBERS, MaterialPush::SIZE),
        "Probe" => (ProbePush::MEMBERS, ProbePush::SIZE),
        "Reproject" => (ReprojectPush::MEMBERS, ReprojectPush::SIZE),
        "ImageStats" => (ImageStatsPush::MEMBERS, ImageStatsPush::SIZE),
        "GBufferResolve" => (GBufferResolvePush::MEMBERS, GBufferResolvePush::SIZE),
        "Overlay" => (OverlayPush::MEMBERS, OverlayPush::SIZE),
        other => panic!("block {other} has no generated struct"),
    }
}

#[test]
fn every_module_declares_the_shared_blocks_as_generated() {
    let mut seen = 0;
    for m in ALL.iter().chain(PROBES) {
        for b in m.blocks {
            let (members, size) = generated(b.name);
            assert_eq!(b.members, members, "{}: block {}", m.label(), b.name);
            assert_eq!(b.size, size, "{}: block {} size", m.label(), b.name);
            seen += 1;
        }
    }
    // Every compute pass reads the frame block, so a reflection that found no block is broken.
    assert!(
        seen >= ALL.len(),
        "only {seen} block declarations reflected"
    );
}

/// Bytes where every 4-byte word holds its own index + 1, so a member read from the wrong
/// offset shows up as the wrong number.
fn numbered<const N: usize>() -> [u8; N] {
    let mut b = [0u8; N];
    for (i, w) in b.chunks_mut(4).enumerate() {
        w.copy_from_slice(&(i as u32 + 1).to_le_bytes());
    }
    b
}

#[test]
fn generated_structs_put_each_member_at_its_reflected_offset() {
    let bytes = numbered::<{ FrameBlock::SIZE }>();
    let frame = FrameBlock::from_bytes(&bytes);
    let word = |offset: usize| offset as u32 / 4 + 1;
    assert_eq!(
        frame.rotation_limit,
        word(FrameBlock::OFFSET_ROTATION_LIMIT)
    );
    assert_eq!(
        frame.size,
        [
            word(FrameBlock::OFFSET_SIZE),
            word(FrameBlock::OFFSET_SIZE + 4)
        ]
    );
    assert_eq!(
        frame.light_near.to_bits(),
        word(FrameBlock::OFFSET_LIGHT_NEAR)
    );
    // Round trip: every member's bytes come back where they were; padding is zero.
    let out = frame.to_bytes();
    for m in FrameBlock::MEMBERS {
        let len = match m.glsl {
            "mat4" => 64,
            "vec4" | "uvec4" | "ivec4" => 16,
            "vec3" | "uvec3" | "ivec3" => 12,
            "vec2" | "uvec2" | "ivec2" => 8,
            _ => 4,
        };
        let r = m.offset..m.offset + len;
        assert_eq!(out[r.clone()], bytes[r], "member {}", m.name);
    }
    let push = EffectPush {
        refresh_rect: [7, 9, 11, 13],
        pattern: 5,
        ..Default::default()
    }
    .to_bytes();
    assert_eq!(push[..8], [7, 0, 0, 0, 9, 0, 0, 0]);
    assert_eq!(push[12], 13);
    let p = EffectPush::MEMBERS
        .iter()
        .find(|m| m.name == "pattern")
        .unwrap();
    assert_eq!(push[p.offset], 5);
    let counters = CountersHeader::from_bytes(&numbered::<{ CountersHeader::SIZE }>());
    assert_eq!(counters.max_blocks, word(CountersHeader::OFFSET_MAX_BLOCKS));
}

#[test]
fn two_shaders_declaring_a_block_differently_fail_the_build() {
    use block_layout::{merge, Block, Member};
    let member = |name: &str, offset, glsl: &'static str| Member {
        name: name.into(),
        offset,
        glsl,
        rust: "f32",
    };
    let a = Block {
        name: "Frame".into(),
        size: 8,
        members: vec![member("near", 0, "float"), member("far", 4, "float")],
    };
    let mut b = a.clone();
    b.members[1] = member("far_plane", 4, "float");
    let mut all = Default::default();
    merge(&mut all, vec![a.clone()], "shaders/a.comp").unwrap();
    merge(&mut all, vec![a.clone()], "shaders/c.comp").expect("identical declarations agree");
    let err = merge(&mut all, vec![b], "shaders/b.comp").unwrap_err();
    assert!(
        err.contains("member 1")
            && err.contains("far at byte 4 in shaders/a.comp")
            && err.contains("far_plane at byte 4 in shaders/b.comp"),
        "{err}"
    );
    let mut moved = a;
    moved.members[1].offset = 8;
    moved.size = 12;
    assert!(merge(&mut all, vec![moved], "shaders/d.comp").is_err());
}

// ------------------------------------------------------------- storage image formats

/// The module of `name` (its first permutation).
fn module_named(name: &str) -> &'static ssgi::shaders::ShaderModuleInfo {
    ALL.iter()
        .copied()
        .find(|m| m.name == name)
        .unwrap_or_else(|| panic!("no module {name}"))
}

/// Every storage image binding's format is reflected, and a pass's temporal images are
/// declared with the formats their images are made with (shared_constants.glsl).
#[test]
fn storage_formats_are_reflected_from_the_shaders() {
    use ssgi::shaders::{AO_HISTORY_FORMAT, MOMENTS_FORMAT, STATE_FORMAT};
    for m in ALL.iter().chain(PROBES) {
        let storage = m
            .bindings
            .iter()
            .filter(|b| b.kind == DescriptorKind::StorageImage)
            .count();
        assert_eq!(m.storage_formats.len(), storage, "{}", m.label());
    }
    let accumulate = module_named("ao/ssao_accumulate.comp");
    assert_eq!(accumulate.storage_format(1, 3), Some(STATE_FORMAT));
    assert_eq!(accumulate.storage_format(1, 4), Some(AO_HISTORY_FORMAT));
    assert_eq!(accumulate.storage_format(1, 6), Some(MOMENTS_FORMAT));
    assert_eq!(accumulate.storage_format(1, 0), None, "a sampled image");
}

/// The planted defect: the AO history bound as an image of another format than the shader's
/// layout qualifier is refused where the pass writes its descriptor sets, naming the pass, the
/// binding, both formats and the image; the same binding with the declared format is accepted.
/// (Every configuration of tests/descriptor_pool.rs binds all its sets through the same check.)
#[test]
fn a_storage_image_of_another_format_than_its_shader_is_refused() {
    use ash::vk;
    use ssgi::passes::decl::{self, Bind, Resolve, Slot, Use};
    use ssgi::shaders::AO_HISTORY_FORMAT;
    use ssgi::vk::{Buffer, Image, ImageDesc};

    struct One<'a>(&'a Image);
    impl Resolve for One<'_> {
        fn image(&self, _: Slot, _: usize) -> Option<&Image> {
            Some(self.0)
        }
        fn buffer(&self, _: Slot) -> Option<&Buffer> {
            None
        }
    }
    let other = if AO_HISTORY_FORMAT == vk::Format::R16G16B16A16_SFLOAT {
        vk::Format::R32G32B32A32_SFLOAT
    } else {
        vk::Format::R16G16B16A16_SFLOAT
    };
    let accumulate = module_named("ao/ssao_accumulate.comp");
    let binds = [Bind::new(4, Slot::History, Use::StorageReadWrite)];
    let ctx = common::context();
    let image = |name: &str, format| {
        Image::new(
            &ctx,
            name,
            ImageDesc {
                width: 4,
                height: 4,
                format,
                usage: vk::ImageUsageFlags::STORAGE,
            },
        )
        .unwrap()
    };
    let planted = image("planted.history", other);
    let err = decl::writes("ssao", accumulate, &binds, &One(&planted), 0)
        .err()
        .expect("a history of another format must be refused")
        .to_string();
    for part in [
        "ssao",
        "binding 4",
        "planted.history",
        &format!("{other:?}"),
        &format!("{AO_HISTORY_FORMAT:?}"),
    ] {
        assert!(err.contains(part), "{err} lacks {part}");
    }
    let right = image("ao.history", AO_HISTORY_FORMAT);
    assert!(decl::writes("ssao", accumulate, &binds, &One(&right), 0).is_ok());
    // A storage image bound where the shader declares none is refused too.
    let nowhere = [Bind::new(0, Slot::GPosition, Use::StorageRead)];
    assert!(decl::writes("ssao", accumulate, &nowhere, &One(&right), 0).is_err());
    drop((planted, right));
    common::assert_clean(&ctx);
}
