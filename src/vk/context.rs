//! The Vulkan context: instance, chosen physical device, logical device with the Vulkan 1.3
//! features ssgi needs, one graphics+compute queue, the allocator and the deletion queue.

use super::debug::DebugNames;
use super::descriptor_counts::DescriptorCounts;
use super::instance::{Instance, ValidationLog};
use crate::error::{Error, Result, VkContext};
use ash::vk;
use gpu_allocator::vulkan::{Allocation, Allocator, AllocatorCreateDesc};
use std::mem::ManuallyDrop;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex};

/// How to create the context.
#[derive(Clone, Debug, Default)]
pub struct ContextOptions {
    /// Validation layers with synchronization validation; messages are recorded.
    pub validation: bool,
    /// Pick the first device whose name contains this (case-insensitive).
    pub device: Option<String>,
    /// Extra instance extensions (window surfaces).
    pub instance_extensions: Vec<&'static std::ffi::CStr>,
    /// Extra device extensions (swapchain).
    pub device_extensions: Vec<&'static std::ffi::CStr>,
    /// Print the chosen device to stderr.
    pub verbose: bool,
}

/// What ssgi reports about the device it runs on.
#[derive(Clone, Debug)]
pub struct DeviceInfo {
    pub name: String,
    pub driver: String,
    pub device_type: String,
    pub api_version: String,
    /// Nanoseconds per timestamp tick.
    pub timestamp_period: f32,
    pub timestamp_valid_bits: u32,
    pub max_push_constants_size: u32,
    /// maxComputeWorkGroupCount: the most workgroups one dispatch has per dimension (at least
    /// 65,535 each; work lists past x continue in y).
    pub max_compute_work_group_count: [u32; 3],
    /// The geometryShader feature (enabled when present): fragment shaders may read
    /// gl_PrimitiveID (the visibility buffer).
    pub geometry_shader: bool,
}

/// Objects whose destruction waits until the GPU finished every submission made before they
/// were dropped.
pub enum Garbage {
    Image(vk::Image),
    ImageView(vk::ImageView),
    Buffer(vk::Buffer),
    Allocation(Allocation),
    Pipeline(vk::Pipeline),
    PipelineLayout(vk::PipelineLayout),
    DescriptorSetLayout(vk::DescriptorSetLayout),
    DescriptorPool(vk::DescriptorPool),
    Sampler(vk::Sampler),
    QueryPool(vk::QueryPool),
}

/// Semaphores of a submission: waited on before the given stages, signalled at the end.
#[derive(Clone, Debug, Default)]
pub struct SubmitSync {
    pub wait: Vec<(vk::Semaphore, vk::PipelineStageFlags2)>,
    pub signal: Vec<vk::Semaphore>,
}

pub struct Context {
    pub device: ash::Device,
    pub physical: vk::PhysicalDevice,
    pub queue: vk::Queue,
    pub queue_family: u32,
    pub info: DeviceInfo,
    /// Most bytes of device memory ssgi lets itself hold (`memory_limit`): allocations past
    /// it fail with a clear out-of-memory error instead of a driver crash or the OOM killer.
    pub memory_limit: u64,
    allocator: ManuallyDrop<Mutex<Allocator>>,
    /// Serial of the last queue submission, and of the last one known complete.
    submitted: AtomicU64,
    completed: AtomicU64,
    garbage: Mutex<Vec<(u64, Garbage)>>,
    /// Descriptors per type that a set of each layout holds, from the bindings the layout was
    /// created with (`pipeline::create_set_layouts`): what descriptor pools size from.
    pub(crate) layout_counts:
        Mutex<std::collections::HashMap<vk::DescriptorSetLayout, DescriptorCounts>>,
    /// Debug names and command labels (no-ops without `VK_EXT_debug_utils`).
    pub names: DebugNames,
    pub instance: Instance,
}

fn device_type_name(t: vk::PhysicalDeviceType) -> &'static str {
    match t {
        vk::PhysicalDeviceType::DISCRETE_GPU => "discrete GPU",
        vk::PhysicalDeviceType::INTEGRATED_GPU => "integrated GPU",
        vk::PhysicalDeviceType::VIRTUAL_GPU => "virtual GPU",
        vk::PhysicalDeviceType::CPU => "CPU",
        _ => "other",
    }
}

fn type_rank(t: vk::PhysicalDeviceType) -> u32 {
    match t {
        vk::PhysicalDeviceType::DISCRETE_GPU => 0,
        vk::PhysicalDeviceType::INTEGRATED_GPU => 1,
        vk::PhysicalDeviceType::VIRTUAL_GPU => 2,
        vk::PhysicalDeviceType::CPU => 3,
        _ => 4,
    }
}

impl Context {
    pub fn new(options: &ContextOptions) -> Result<Arc<Self>> {
        let ext_ptrs: Vec<_> = options
            .instance_extensions
            .iter()
            .map(|e| e.as_ptr())
            .collect();
        let instance = Instance::new(options.validation, &ext_ptrs)?;
        let (physical, queue_family, info) = pick_device(&instance, options)?;
        if options.verbose {
            eprintln!(
                "device: {} ({}, driver {}, Vulkan {})",
                info.name, info.device_type, info.driver, info.api_version
            );
        }
        let priorities = [1.0f32];
        let queue_info = [vk::DeviceQueueCreateInfo::default()
            .queue_family_index(queue_family)
            .queue_priorities(&priorities)];
        let mut f13 = vk::PhysicalDeviceVulkan13Features::default()
            .dynamic_rendering(true)
            .synchronization2(true);
        let mut f12 = vk::PhysicalDeviceVulkan12Features::default().host_query_reset(true);
        let ext_ptrs: Vec<_> = options
            .device_extensions
            .iter()
            .map(|e| e.as_ptr())
            .collect();
        let core = vk::PhysicalDeviceFeatures::default().geometry_shader(info.geometry_shader);
        let device_info = vk::DeviceCreateInfo::default()
            .queue_create_infos(&queue_info)
            .enabled_features(&core)
            .enabled_extension_names(&ext_ptrs)
            .push_next(&mut f13)
            .push_next(&mut f12);
        // SAFETY: `physical` came from this instance; the create info references locals only.
        let device = unsafe { instance.raw.create_device(physical, &device_info, None) }
            .vk("vkCreateDevice")?;
        let names = DebugNames::new(&instance.raw, &device, instance.debug_utils);
        // SAFETY: the family and index were requested in `queue_info`.
        let queue = unsafe { device.get_device_queue(queue_family, 0) };
        let allocator = Allocator::new(&AllocatorCreateDesc {
            instance: instance.raw.clone(),
            device: device.clone(),
            physical_device: physical,
            debug_settings: Default::default(),
            buffer_device_address: false,
            allocation_sizes: Default::default(),
        })
        .map_err(|e| Error::Allocation {
            name: "allocator".into(),
            message: e.to_string(),
        })?;
        // SAFETY: a query on the physical device this context was created from.
        let memory = unsafe { instance.raw.get_physical_device_memory_properties(physical) };
        let memory_limit = memory_limit(&memory, &info, host_available_bytes());
        Ok(Arc::new(Context {
            device,
            physical,
            queue,
            queue_family,
            info,
            memory_limit,
            allocator: ManuallyDrop::new(Mutex::new(allocator)),
            submitted: AtomicU64::new(0),
            completed: AtomicU64::new(0),
            layout_counts: Mutex::new(std::collections::HashMap::new()),
            garbage: Mutex::new(Vec::new()),
            names,
            instance,
        }))
    }

    pub fn validation(&self) -> Option<&Arc<ValidationLog>> {
        self.instance.validation.as_ref()
    }

    pub fn allocator(&self) -> std::sync::MutexGuard<'_, Allocator> {
        // A poisoned lock only means another thread panicked mid-allocation; the allocator's
        // own state is still consistent for freeing.
        self.allocator.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Submit one command buffer; returns the submission's serial for `mark_complete`.
    pub fn submit(&self, cmd: vk::CommandBuffer, fence: vk::Fence) -> Result<u64> {
        self.submit_with(cmd, fence, &SubmitSync::default())
    }

    /// Submit with semaphores (swapchain acquire / present).
    pub fn submit_with(
        &self,
        cmd: vk::CommandBuffer,
        fence: vk::Fence,
        sync: &SubmitSync,
    ) -> Result<u64> {
        let cmds = [vk::CommandBufferSubmitInfo::default().command_buffer(cmd)];
        let waits: Vec<_> = sync
            .wait
            .iter()
            .map(|(s, stage)| {
                vk::SemaphoreSubmitInfo::default()
                    .semaphore(*s)
                    .stage_mask(*stage)
            })
            .collect();
        let signals: Vec<_> = sync
            .signal
            .iter()
            .map(|s| {
                vk::SemaphoreSubmitInfo::default()
                    .semaphore(*s)
                    .stage_mask(vk::PipelineStageFlags2::ALL_COMMANDS)
            })
            .collect();
        let submit = [vk::SubmitInfo2::default()
            .command_buffer_infos(&cmds)
            .wait_semaphore_infos(&waits)
            .signal_semaphore_infos(&signals)];
        // SAFETY: `cmd` is fully recorded, `fence` unsignalled; access to the queue is
        // single-threaded (the renderer owns the only submitting thread).
        unsafe { self.device.queue_submit2(self.queue, &submit, fence) }.vk("vkQueueSubmit2")?;
        Ok(self.submitted.fetch_add(1, Ordering::SeqCst) + 1)
    }

    /// The GPU finished submission `serial` (its fence signalled): free what waited on it.
    pub fn mark_complete(&self, serial: u64) {
        self.completed.fetch_max(serial, Ordering::SeqCst);
        let done = self.completed.load(Ordering::SeqCst);
        let ready: Vec<Garbage> = {
            let mut g = self.garbage.lock().unwrap_or_else(|e| e.into_inner());
            let (ready, keep): (Vec<_>, Vec<_>) = g.drain(..).partition(|(s, _)| *s <= done);
            *g = keep;
            ready.into_iter().map(|(_, x)| x).collect()
        };
        for item in ready {
            self.destroy(item);
        }
    }

    /// Wait for the device to go idle and free everything pending.
    pub fn wait_idle(&self) -> Result<()> {
        // SAFETY: plain device-level wait.
        unsafe { self.device.device_wait_idle() }.vk("vkDeviceWaitIdle")?;
        self.mark_complete(self.submitted.load(Ordering::SeqCst));
        Ok(())
    }

    /// Destroy `item` once every submission made so far has completed.
    pub fn defer(&self, item: Garbage) {
        let serial = self.submitted.load(Ordering::SeqCst);
        if serial <= self.completed.load(Ordering::SeqCst) {
            self.destroy(item);
        } else {
            let mut g = self.garbage.lock().unwrap_or_else(|e| e.into_inner());
            g.push((serial, item));
        }
    }

    fn destroy(&self, item: Garbage) {
        // SAFETY: `defer` only hands items here once the GPU finished every submission that
        // could use them, and nothing on the CPU holds them any more.
        unsafe {
            match item {
                Garbage::Image(x) => self.device.destroy_image(x, None),
                Garbage::ImageView(x) => self.device.destroy_image_view(x, None),
                Garbage::Buffer(x) => self.device.destroy_buffer(x, None),
                Garbage::Allocation(a) => {
                    // Freeing can only fail for a foreign allocation; nothing to recover.
                    let _ = self.allocator().free(a);
                }
                Garbage::Pipeline(x) => self.device.destroy_pipeline(x, None),
                Garbage::PipelineLayout(x) => self.device.destroy_pipeline_layout(x, None),
                Garbage::DescriptorSetLayout(x) => {
                    self.device.destroy_descriptor_set_layout(x, None)
                }
                Garbage::DescriptorPool(x) => self.device.destroy_descriptor_pool(x, None),
                Garbage::Sampler(x) => self.device.destroy_sampler(x, None),
                Garbage::QueryPool(x) => self.device.destroy_query_pool(x, None),
            }
        }
    }
}

impl Drop for Context {
    fn drop(&mut self) {
        // SAFETY: last owner of the device: wait for the GPU, free what is pending, drop the
        // allocator (it frees its memory blocks through the device) and then the device.
        unsafe {
            let _ = self.device.device_wait_idle();
            let pending: Vec<_> = self
                .garbage
                .lock()
                .map(|mut g| g.drain(..).map(|(_, x)| x).collect())
                .unwrap_or_default();
            for item in pending {
                self.destroy(item);
            }
            ManuallyDrop::drop(&mut self.allocator);
            self.device.destroy_device(None);
        }
    }
}

/// The device-memory budget: the largest device-local heap. A CPU device's (lavapipe's)
/// "device memory" is host memory whatever heap size it reports (Mesa 22.3 says 2 GiB and
/// does not enforce it): there, 90% of what the host has available now, so a huge `--size`
/// fails with a message rather than swapping or waking the OOM killer.
fn memory_limit(
    memory: &vk::PhysicalDeviceMemoryProperties,
    info: &DeviceInfo,
    host_available: Option<u64>,
) -> u64 {
    let heaps =
        &memory.memory_heaps[..(memory.memory_heap_count as usize).min(vk::MAX_MEMORY_HEAPS)];
    let device_local = heaps
        .iter()
        .filter(|h| h.flags.contains(vk::MemoryHeapFlags::DEVICE_LOCAL))
        .map(|h| h.size)
        .max()
        .or_else(|| heaps.iter().map(|h| h.size).max())
        .unwrap_or(u64::MAX);
    match (info.device_type.as_str(), host_available) {
        ("CPU", Some(host)) => host / 10 * 9,
        _ => device_local,
    }
}

/// `MemAvailable` of /proc/meminfo in bytes (Linux), if readable.
fn host_available_bytes() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}

fn pick_device(
    instance: &Instance,
    options: &ContextOptions,
) -> Result<(vk::PhysicalDevice, u32, DeviceInfo)> {
    // SAFETY: enumeration on a live instance.
    let devices =
        unsafe { instance.raw.enumerate_physical_devices() }.vk("vkEnumeratePhysicalDevices")?;
    let mut candidates = Vec::new();
    let mut rejected = Vec::new();
    for pd in devices {
        let mut driver = vk::PhysicalDeviceDriverProperties::default();
        let mut props2 = vk::PhysicalDeviceProperties2::default().push_next(&mut driver);
        let mut f13 = vk::PhysicalDeviceVulkan13Features::default();
        let mut f12 = vk::PhysicalDeviceVulkan12Features::default();
        let mut feats = vk::PhysicalDeviceFeatures2::default()
            .push_next(&mut f13)
            .push_next(&mut f12);
        // SAFETY: queries on a device enumerated from this instance; the chains are local.
        let families = unsafe {
            instance
                .raw
                .get_physical_device_properties2(pd, &mut props2);
            instance.raw.get_physical_device_features2(pd, &mut feats);
            instance.raw.get_physical_device_queue_family_properties(pd)
        };
        let geometry_shader = feats.features.geometry_shader != 0;
        let props = props2.properties;
        let name = props
            .device_name_as_c_str()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        if let Some(want) = &options.device {
            if !name.to_lowercase().contains(&want.to_lowercase()) {
                rejected.push(format!("{name}: does not match --device {want:?}"));
                continue;
            }
        }
        let v = props.api_version;
        if vk::api_version_major(v) == 1 && vk::api_version_minor(v) < 3 {
            rejected.push(format!("{name}: Vulkan 1.3 required"));
            continue;
        }
        if f13.dynamic_rendering == 0 || f13.synchronization2 == 0 || f12.host_query_reset == 0 {
            rejected.push(format!(
                "{name}: needs dynamicRendering, synchronization2 and hostQueryReset"
            ));
            continue;
        }
        let need = vk::QueueFlags::GRAPHICS | vk::QueueFlags::COMPUTE;
        let Some(family) = families
            .iter()
            .position(|f| f.queue_flags.contains(need) && f.timestamp_valid_bits > 0)
        else {
            rejected.push(format!("{name}: no graphics+compute queue with timestamps"));
            continue;
        };
        let driver_name = driver
            .driver_info_as_c_str()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        let info = DeviceInfo {
            name,
            driver: format!(
                "{} {}",
                driver
                    .driver_name_as_c_str()
                    .map(|s| s.to_string_lossy().into_owned())
                    .unwrap_or_default(),
                driver_name
            )
            .trim()
            .to_string(),
            device_type: device_type_name(props.device_type).to_string(),
            api_version: format!(
                "{}.{}.{}",
                vk::api_version_major(v),
                vk::api_version_minor(v),
                vk::api_version_patch(v)
            ),
            timestamp_period: props.limits.timestamp_period,
            timestamp_valid_bits: families[family].timestamp_valid_bits,
            max_push_constants_size: props.limits.max_push_constants_size,
            max_compute_work_group_count: props.limits.max_compute_work_group_count,
            geometry_shader,
        };
        candidates.push((type_rank(props.device_type), pd, family as u32, info));
    }
    candidates.sort_by_key(|c| c.0);
    match candidates.into_iter().next() {
        Some((_, pd, family, info)) => Ok((pd, family, info)),
        None if rejected.is_empty() => Err(Error::NoDevice(
            "the loader lists no Vulkan devices (is mesa-vulkan-drivers installed?)".into(),
        )),
        None => Err(Error::NoDevice(rejected.join("; "))),
    }
}
