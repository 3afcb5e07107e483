//! Descriptor pools sized from the declarations: every configuration that changes which passes
//! exist builds, renders a frame under validation, and allocated exactly the descriptors its
//! sets' layouts declare, within the sizes each Vulkan pool was created with. Lavapipe never
//! refuses an allocation past a pool's sizes (NVIDIA does: CCIPCA failed there with
//! ERROR_OUT_OF_POOL_MEMORY when the pool was a guess), so the accounting is checked here.

mod common;

use ssgi::config::antialias::AaMode;
use ssgi::config::{Effects, GBufferMode, IndirectFilter, RenderConfig};
use ssgi::renderer::Renderer;
use ssgi::scene::cornell_box;
use ssgi::vk::DescriptorCounts;

fn configs() -> Vec<(&'static str, RenderConfig)> {
    let base = RenderConfig {
        width: 32,
        height: 32,
        rsm_size: 32,
        skip_unchanged: false,
        ..Default::default()
    };
    let with = |f: &dyn Fn(&mut RenderConfig)| {
        let mut c = base;
        f(&mut c);
        c
    };
    let ssdo = Effects {
        direct: true,
        indirect: true,
        ssdo: true,
        ..Effects::NONE
    };
    vec![
        ("default", base),
        ("no reuse", with(&|c| c.temporal.reuse = false)),
        (
            "full-resolution gather",
            with(&|c| c.indirect.half_res = false),
        ),
        ("interleave 2", with(&|c| c.indirect.interleave = 2)),
        (
            "ccipca",
            with(&|c| c.indirect.filter = IndirectFilter::Ccipca),
        ),
        (
            "ccipca 7 bases",
            with(&|c| {
                c.indirect.filter = IndirectFilter::Ccipca;
                c.ccipca.bases = 7;
            }),
        ),
        (
            "jbf11",
            with(&|c| c.indirect.filter = IndirectFilter::Jbf11),
        ),
        ("svgf", with(&|c| c.indirect.filter = IndirectFilter::Svgf)),
        ("ssdo", with(&|c| c.effects = ssdo)),
        (
            "ssdo cached",
            with(&|c| {
                c.effects = ssdo;
                c.temporal.reuse = true;
            }),
        ),
        (
            "ssdo uncached",
            with(&|c| {
                c.effects = ssdo;
                c.temporal.reuse = false;
            }),
        ),
        ("ao position mips", with(&|c| c.ao.position_mips = 2)),
        ("sraa", with(&|c| c.aa.mode = AaMode::Sraa)),
        (
            "sraa-shadow + ccipca",
            with(&|c| {
                c.aa.mode = AaMode::SraaShadow;
                c.indirect.filter = IndirectFilter::Ccipca;
            }),
        ),
        ("ssaa16", with(&|c| c.aa.mode = AaMode::Ssaa16)),
        (
            "visibility gbuffer",
            with(&|c| c.gbuffer = GBufferMode::Visibility),
        ),
    ]
}

#[test]
fn every_configuration_allocates_within_its_pools_declared_sizes() {
    let ctx = common::context();
    for (name, config) in configs() {
        let mut r =
            Renderer::new(&ctx, cornell_box(), config).unwrap_or_else(|e| panic!("{name}: {e}"));
        let camera = r.scene.camera;
        r.render_frame(&camera)
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        r.finish().unwrap();
        let pool = r.descriptor_pool();
        let (sets, allocated) = pool.allocated();
        let capacities = pool.capacities();
        let (mut declared_sets, mut used_sets) = (0, 0);
        let mut used = DescriptorCounts::default();
        for ((sets_declared, sizes), (sets_left, left)) in &capacities {
            assert!(sets_left <= sets_declared, "{name}");
            declared_sets += sets_declared;
            used_sets += sets_declared - sets_left;
            for t in 0..5 {
                assert!(
                    left.0[t] <= sizes.0[t],
                    "{name}: type {t} past its pool's size"
                );
                used.0[t] += sizes.0[t] - left.0[t];
            }
        }
        eprintln!(
            "{name}: {sets} sets, descriptors per type {:?}, in {} pools of {declared_sets} sets",
            allocated.0,
            capacities.len()
        );
        assert!(sets > 8, "{name}: {sets} sets");
        assert_eq!(used_sets, sets, "{name}: every set counted against a pool");
        assert_eq!(
            used, allocated,
            "{name}: every descriptor counted against a pool"
        );
        drop(r);
    }
    common::assert_clean(&ctx);
}
