//! Antialiasing (`--aa`) on the built-in `tilted-quad` scene, direct light with hard shadows,
//! against 16x supersampling. The subpixels of the rotated grid are samples of the 4x render
//! too (both sit at odd eighths of the pixel), so the 4x G-buffer tells which surface and which
//! side of a shadow edge every subpixel lies on.

mod common;

use ssgi::config::antialias::{AaConfig, AaMode};
use ssgi::config::pcf::Pcf;
use ssgi::config::Effects;
use ssgi::renderer::{RenderConfig, Renderer};
use ssgi::resources::targets::Target;
use ssgi::vk::{Context, ImageData};
use std::sync::Arc;

const SIZE: u32 = 64;

/// The rotated grid's subpixels as texels of the 4x render inside pixel (0, 0)
/// (shaders/include/subpixel.glsl: offsets (-1/8, -3/8), (3/8, -1/8), (-3/8, 1/8), (1/8, 3/8)).
const SUBPIXELS: [(u32, u32); 4] = [(1, 0), (3, 1), (0, 2), (2, 3)];

fn render(ctx: &Arc<Context>, mode: AaMode) -> Renderer {
    let config = RenderConfig {
        width: SIZE,
        height: SIZE,
        rsm_size: 512,
        pcf: Pcf::HARD,
        effects: Effects {
            direct: true,
            ..Effects::NONE
        },
        aa: AaConfig {
            mode,
            ..AaConfig::default()
        },
        ..Default::default()
    };
    let mut r = Renderer::new(ctx, ssgi::scene::tilted_quad(), config).expect("renderer");
    let camera = r.scene.camera;
    r.render_frame(&camera).expect("frame");
    r.finish().expect("finish");
    r
}

fn rgb(image: &ImageData, x: u32, y: u32) -> [f32; 3] {
    let t = image.texel(x, y);
    [t[0], t[1], t[2]]
}

/// Per output pixel, from the 4x render: whether all 16 samples lie on one surface (one
/// albedo), whether its 4 subpixels do and share the surface of the pixel centre (`centre`,
/// the 1x G-buffer albedo), and whether its 16 samples disagree on the hard shadow.
struct Classes {
    geometric_edge: Vec<bool>,
    interior: Vec<bool>,
    shadow_edge: Vec<bool>,
}

fn classify(albedo4: &ImageData, shadow4: &ImageData, centre: &ImageData) -> Classes {
    let n = (SIZE * SIZE) as usize;
    let mut c = Classes {
        geometric_edge: vec![false; n],
        interior: vec![false; n],
        shadow_edge: vec![false; n],
    };
    for y in 0..SIZE {
        for x in 0..SIZE {
            let i = (y * SIZE + x) as usize;
            let at = |sx: u32, sy: u32| (4 * x + sx, 4 * y + sy);
            let first = rgb(albedo4, 4 * x, 4 * y);
            let mut one_surface = true;
            let (mut lit, mut dark) = (false, false);
            for sy in 0..4 {
                for sx in 0..4 {
                    let (u, v) = at(sx, sy);
                    one_surface &= rgb(albedo4, u, v) == first;
                    let s = shadow4.texel(u, v)[3];
                    lit |= s > 0.5;
                    dark |= s <= 0.5;
                }
            }
            let own = rgb(centre, x, y);
            c.interior[i] = SUBPIXELS.iter().all(|&(sx, sy)| {
                let (u, v) = at(sx, sy);
                rgb(albedo4, u, v) == own
            });
            c.geometric_edge[i] = !one_surface;
            c.shadow_edge[i] = one_surface && lit && dark;
        }
    }
    c
}

/// RMSE of `image` against `reference` over the pixels `mask` selects (RGB, encoded values).
fn rmse(image: &ImageData, reference: &ImageData, mask: &[bool]) -> f64 {
    let (mut sum, mut count) = (0.0f64, 0usize);
    for y in 0..SIZE {
        for x in 0..SIZE {
            if !mask[(y * SIZE + x) as usize] {
                continue;
            }
            let (a, b) = (rgb(image, x, y), rgb(reference, x, y));
            sum += (0..3).map(|k| ((a[k] - b[k]) as f64).powi(2)).sum::<f64>();
            count += 3;
        }
    }
    assert!(count > 0, "no pixel selected");
    (sum / count as f64).sqrt()
}

#[test]
fn sraa_halves_the_edge_error_keeps_interiors_and_shadow_weights_help() {
    let ctx = common::context();
    let mut ssaa = render(&ctx, AaMode::Ssaa16);
    let reference = common::read(&mut ssaa, Target::Output);
    let albedo4 = common::read(&mut ssaa, Target::GAlbedo);
    let shadow4 = common::read(&mut ssaa, Target::Direct);
    assert_eq!((reference.width, albedo4.width), (SIZE, 4 * SIZE));
    let mut none = render(&ctx, AaMode::None);
    let plain = common::read(&mut none, Target::Output);
    let centre = common::read(&mut none, Target::GAlbedo);
    let classes = classify(&albedo4, &shadow4, &centre);
    let count = |m: &[bool]| m.iter().filter(|b| **b).count();
    let (edges, shadow_edges) = (count(&classes.geometric_edge), count(&classes.shadow_edge));
    assert!(edges > 40 && shadow_edges > 40, "{edges} {shadow_edges}");

    let mut sraa = render(&ctx, AaMode::Sraa);
    let sraa_out = common::read(&mut sraa, Target::Output);
    // Shading ran once per output pixel: the direct light and the composite are output-sized
    // (with 16x supersampling they were 16 times the pixels, checked above).
    assert_eq!(common::read(&mut sraa, Target::Direct).width, SIZE);
    assert_eq!(common::read(&mut sraa, Target::Shaded).width, SIZE);
    let mut sraa_shadow = render(&ctx, AaMode::SraaShadow);
    let shadow_out = common::read(&mut sraa_shadow, Target::Output);

    let e_none = rmse(&plain, &reference, &classes.geometric_edge);
    let e_sraa = rmse(&sraa_out, &reference, &classes.geometric_edge);
    println!("geometric edges ({edges} px): none {e_none:.4}, sraa {e_sraa:.4}");
    assert!(e_sraa <= 0.5 * e_none, "{e_sraa} vs {e_none}");

    let mut worst = 0.0f32;
    for y in 0..SIZE {
        for x in 0..SIZE {
            if classes.interior[(y * SIZE + x) as usize] {
                let (a, b) = (rgb(&sraa_out, x, y), rgb(&plain, x, y));
                worst = (0..3).map(|k| (a[k] - b[k]).abs()).fold(worst, f32::max);
            }
        }
    }
    println!(
        "interior pixels ({}): largest change {worst}",
        count(&classes.interior)
    );
    assert!(worst <= 1e-3, "{worst}");

    let s_sraa = rmse(&sraa_out, &reference, &classes.shadow_edge);
    let s_shadow = rmse(&shadow_out, &reference, &classes.shadow_edge);
    println!("shadow edges ({shadow_edges} px): sraa {s_sraa:.4}, sraa-shadow {s_shadow:.4}");
    assert!(s_shadow < s_sraa, "{s_shadow} vs {s_sraa}");
    common::assert_clean(&ctx);
}
