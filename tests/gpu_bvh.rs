//! The GPU's BVH traversal (shaders/include/bvh.glsl over scene::flat_bvh, issue 64) finds the
//! hits the CPU reference's tracer (scene::accel, obvhs's CWBVH) finds: the same closest
//! triangle at the same distance, and the same answer to "is anything in [t_min, t_max]", for
//! thousands of rays through the built-in scenes, under validation.

mod common;

use ash::vk;
use glam::Vec3;
use gpu_allocator::MemoryLocation;
use ssgi::scene::accel::Accel;
use ssgi::scene::flat_bvh::FlatBvh;
use ssgi::scene::{load_scene, Mesh};
use ssgi::shaders::{DescriptorKind, ReflectedBinding, BVH_RAYS_COMP};
use ssgi::vk::recorder::Recorder;
use ssgi::vk::{one_shot, Access, Buffer, Context, DescriptorPool, Pipeline, SetWriter, Tracker};
use std::sync::Arc;

/// A ray: origin, t_min, unit direction, t_max.
#[derive(Clone, Copy, Debug)]
struct Ray {
    origin: Vec3,
    t_min: f32,
    dir: Vec3,
    t_max: f32,
}

/// What the probe wrote for a ray: the closest t and triangle (None: no hit), and bvh_any.
#[derive(Clone, Copy, Debug)]
struct GpuHit {
    closest: Option<(f32, u32)>,
    any: bool,
}

/// `n` rays from points in the scene's box (slightly enlarged) in uniform directions; every
/// fourth is a short segment (the any-hit and t_max paths), the others reach the far side.
fn rays(mesh: &Mesh, n: usize) -> Vec<Ray> {
    let b = mesh.bounds;
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut next = || {
        // xorshift64*: deterministic, no dependency.
        state ^= state >> 12;
        state ^= state << 25;
        state ^= state >> 27;
        ((state.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 40) as f32) / (1u64 << 24) as f32
    };
    let size = b.max - b.min;
    (0..n)
        .map(|i| {
            let origin = b.min - 0.05 * size + 1.1 * size * Vec3::new(next(), next(), next());
            let z = 2.0 * next() - 1.0;
            let phi = std::f32::consts::TAU * next();
            let r = (1.0 - z * z).max(0.0).sqrt();
            let dir = Vec3::new(r * phi.cos(), r * phi.sin(), z);
            let t_max = if i % 4 == 3 {
                0.2 * size.length() * next()
            } else {
                1e30
            };
            Ray {
                origin,
                t_min: 0.0,
                dir,
                t_max,
            }
        })
        .collect()
}

fn storage(ctx: &Arc<Context>, name: &str, bytes: usize, location: MemoryLocation) -> Buffer {
    Buffer::new(
        ctx,
        name,
        bytes.max(16) as u64,
        vk::BufferUsageFlags::STORAGE_BUFFER,
        location,
    )
    .unwrap()
}

/// The probe's answers for `rays` through `flat`.
fn trace_on_gpu(ctx: &Arc<Context>, flat: &FlatBvh, rays: &[Ray]) -> Vec<GpuHit> {
    let mut ray_bytes = Vec::with_capacity(rays.len() * 32);
    for r in rays {
        for c in [
            r.origin.x, r.origin.y, r.origin.z, r.t_min, r.dir.x, r.dir.y, r.dir.z, r.t_max,
        ] {
            ray_bytes.extend_from_slice(&c.to_le_bytes());
        }
    }
    let mut ray_buffer = storage(
        ctx,
        "bvh probe rays",
        ray_bytes.len(),
        MemoryLocation::CpuToGpu,
    );
    ray_buffer.write(&ray_bytes).unwrap();
    let mut nodes = storage(ctx, "bvh nodes", flat.nodes.len(), MemoryLocation::CpuToGpu);
    nodes.write(&flat.nodes).unwrap();
    let mut triangles = storage(
        ctx,
        "bvh triangles",
        flat.triangles.len(),
        MemoryLocation::CpuToGpu,
    );
    triangles.write(&flat.triangles).unwrap();
    let hits = storage(
        ctx,
        "bvh probe hits",
        16 * rays.len(),
        MemoryLocation::GpuToCpu,
    );
    let declared: Vec<ReflectedBinding> = (0..4)
        .map(|binding| ReflectedBinding {
            set: 0,
            binding,
            kind: DescriptorKind::StorageBuffer,
            count: 1,
        })
        .collect();
    let pipeline = Pipeline::compute(ctx, "bvh_rays", &BVH_RAYS_COMP, &declared).unwrap();
    let pool = DescriptorPool::new(ctx).unwrap();
    let set = pool.allocate(pipeline.set_layouts[0], "bvh probe").unwrap();
    SetWriter::new()
        .storage_buffer(0, &ray_buffer)
        .storage_buffer(1, &hits)
        .storage_buffer(2, &nodes)
        .storage_buffer(3, &triangles)
        .write(ctx, set);
    one_shot(ctx, |cmd| {
        let mut tracker = Tracker::new();
        for b in [&ray_buffer, &nodes, &triangles] {
            tracker.buffer(b, Access::ComputeStorageRead);
        }
        tracker.buffer(&hits, Access::ComputeStorageWrite);
        tracker.flush(&ctx.device, cmd);
        let rec = Recorder::new(ctx, cmd);
        rec.bind(&pipeline, &[set]);
        rec.dispatch_2d(&pipeline, rays.len() as u32, 1);
        tracker.buffer(&hits, Access::HostRead);
        tracker.flush(&ctx.device, cmd);
        Ok(())
    })
    .unwrap();
    hits.mapped().unwrap()[..16 * rays.len()]
        .chunks_exact(16)
        .map(|c| {
            let word = |i: usize| u32::from_le_bytes(c[4 * i..4 * i + 4].try_into().unwrap());
            let t = f32::from_bits(word(0));
            let triangle = word(1);
            GpuHit {
                closest: (triangle != u32::MAX).then_some((t, triangle)),
                any: f32::from_bits(word(2)) == 1.0,
            }
        })
        .collect()
}

/// Rays whose GPU answer differs from the CPU's: the closest hit's presence, triangle or
/// distance (1e-5 relative; another triangle at the same distance is an edge both share), or
/// the any-hit answer.
fn disagreements(mesh: &Mesh, rays: &[Ray], gpu: &[GpuHit]) -> Vec<String> {
    let accel = Accel::new(mesh);
    let mut out = Vec::new();
    for (i, (r, g)) in rays.iter().zip(gpu).enumerate() {
        let cpu = accel.closest(r.origin, r.dir, r.t_min, r.t_max, None);
        let same = match (cpu, g.closest) {
            (None, None) => true,
            (Some(c), Some((t, tri))) => {
                let close = (c.t - t).abs() <= 1e-5 * c.t.max(1.0);
                close && (c.triangle as u32 == tri || (c.t - t).abs() <= 1e-6 * c.t.max(1.0))
            }
            _ => false,
        };
        if !same || g.any != cpu.is_some() {
            out.push(format!(
                "ray {i} {r:?}: CPU {:?}, GPU {:?}",
                cpu.map(|c| (c.t, c.triangle)),
                g
            ));
        }
    }
    out
}

#[test]
fn gpu_traversal_finds_the_cpu_tracers_hits() {
    let ctx = common::context();
    for name in ["cornell-box", "pyramids", "tilted-quad"] {
        let scene = load_scene(name, None).unwrap();
        let flat = FlatBvh::new(&scene.mesh).unwrap();
        let rays = rays(&scene.mesh, 4096);
        let gpu = trace_on_gpu(&ctx, &flat, &rays);
        let hits = gpu.iter().filter(|g| g.closest.is_some()).count();
        // The rays must test something: many hit (a quarter of them at least in the closed
        // box; a lone quad takes fewer), some miss (they start outside too).
        assert!(
            hits > rays.len() / 20 && hits < rays.len(),
            "{name}: {hits} of {} rays hit",
            rays.len()
        );
        let wrong = disagreements(&scene.mesh, &rays, &gpu);
        eprintln!(
            "{name}: {} rays, {hits} hit, {} disagree",
            rays.len(),
            wrong.len()
        );
        // Rays through a shared edge or vertex may take either side in either tracer's
        // rounding; anything beyond a handful is a traversal error.
        assert!(
            wrong.len() <= rays.len() / 1000,
            "{name}: {} of {} rays disagree, e.g. {:?}",
            wrong.len(),
            rays.len(),
            &wrong[..wrong.len().min(3)]
        );
    }
    common::assert_clean(&ctx);
}

/// A scene without triangles: one empty root box, which every ray misses.
#[test]
fn an_empty_scene_is_missed() {
    let ctx = common::context();
    let empty = Mesh::default();
    let flat = FlatBvh::new(&empty).unwrap();
    let ray = Ray {
        origin: Vec3::ZERO,
        t_min: 0.0,
        dir: Vec3::X,
        t_max: 1e30,
    };
    let gpu = trace_on_gpu(&ctx, &flat, &[ray]);
    assert!(gpu[0].closest.is_none() && !gpu[0].any);
    common::assert_clean(&ctx);
}
