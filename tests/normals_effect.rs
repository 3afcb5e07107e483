//! The normals debug effect (`--effects normals`, src/effects/normals/): its composite term is
//! each pixel's G-buffer normal mapped to n * 0.5 + 0.5, and nothing on the background,
//! checked against the G-buffer read back and mapped on the CPU. Beside the direct light it is
//! one more radiance term, and the composite adds it. Under validation.

mod common;

use ssgi::config::pcf::Pcf;
use ssgi::config::Effects;
use ssgi::effects::TermKind;
use ssgi::renderer::{RenderConfig, Renderer};
use ssgi::resources::targets::Target;

const SIZE: u32 = 48;

fn render(effects: Effects) -> (Renderer, std::sync::Arc<ssgi::vk::Context>) {
    let ctx = common::context();
    let config = RenderConfig {
        width: SIZE,
        height: SIZE,
        rsm_size: 128,
        pcf: Pcf::HARD,
        effects,
        ..Default::default()
    };
    // The box from twice as far: its walls, and background around them.
    let mut scene = ssgi::scene::cornell_box();
    let c = &mut scene.camera;
    c.position = c.target + (c.position - c.target) * 2.0;
    let mut r = Renderer::new(&ctx, scene, config).expect("renderer");
    let camera = r.scene.camera;
    r.render_frame(&camera).expect("frame");
    r.finish().expect("finish");
    (r, ctx)
}

#[test]
fn the_term_is_the_gbuffer_normal_mapped_to_colour() {
    let (mut r, ctx) = render(Effects {
        normals: true,
        ..Effects::NONE
    });
    let (kind, term) = r.read_term(ssgi::effects::normals::ID).expect("term");
    assert_eq!(kind, TermKind::Radiance);
    let position = common::read(&mut r, Target::GPosition);
    let normal = common::read(&mut r, Target::GNormal);
    let (mut surface, mut background) = (0, 0);
    for y in 0..SIZE {
        for x in 0..SIZE {
            let got = term.texel(x, y);
            let want: [f32; 3] = if position.texel(x, y)[3] != 0.0 {
                surface += 1;
                let n = normal.texel(x, y);
                [n[0] * 0.5 + 0.5, n[1] * 0.5 + 0.5, n[2] * 0.5 + 0.5]
            } else {
                background += 1;
                [0.0; 3]
            };
            for c in 0..3 {
                // One fused multiply-add against two roundings: at most an ulp of 1.
                assert!(
                    (got[c] - want[c]).abs() <= 1.2e-7,
                    "({x}, {y}) channel {c}: {} != {}",
                    got[c],
                    want[c]
                );
            }
        }
    }
    // The box covers a fifth of the view from twice as far; the rest is background.
    assert!(
        surface > (SIZE * SIZE / 8) as usize,
        "{surface} surface pixels"
    );
    assert!(background > 0, "no background pixel to check");
    common::assert_clean(&ctx);
}

#[test]
fn the_composite_adds_it_as_one_more_radiance_term() {
    let direct = Effects {
        direct: true,
        ..Effects::NONE
    };
    let (mut alone, _ctx) = render(direct);
    let (mut with, ctx) = render(Effects {
        normals: true,
        ..direct
    });
    let (_, term) = with.read_term(ssgi::effects::normals::ID).expect("term");
    let (_, light) = with.read_term(ssgi::effects::direct::ID).expect("term");
    let (_, light_alone) = alone.read_term(ssgi::effects::direct::ID).expect("term");
    let out = common::read(&mut with, Target::Output);
    let out_alone = common::read(&mut alone, Target::Output);
    // The direct light does not depend on the normals effect, and where the normals term is
    // bright the output is brighter than without it (the composite tonemaps, so compare order,
    // not sums).
    let mut brighter = 0;
    for y in 0..SIZE {
        for x in 0..SIZE {
            assert_eq!(light.texel(x, y), light_alone.texel(x, y), "({x}, {y})");
            let t = term.texel(x, y);
            let (a, b) = (out.texel(x, y), out_alone.texel(x, y));
            if t[0] + t[1] + t[2] > 0.3 {
                assert!(a[0] + a[1] + a[2] > b[0] + b[1] + b[2], "({x}, {y})");
                brighter += 1;
            } else if t == [0.0, 0.0, 0.0, 1.0] {
                assert_eq!(a, b, "({x}, {y}): no term, same output");
            }
        }
    }
    assert!(
        brighter > (SIZE * SIZE / 8) as usize,
        "{brighter} brighter pixels"
    );
    common::assert_clean(&ctx);
}
