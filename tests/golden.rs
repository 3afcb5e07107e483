//! Golden-image regression: 64x64 renders of the Cornell box and the bunny in a box for every
//! combination of effects, with reuse on and off, against PNGs in `tests/golden/`.
//!
//! The goldens pin the renderer's behaviour across refactors; a change that is meant to move
//! pixels re-renders them in its own commit and says why (the last: the G-buffer's albedo in
//! fp16 instead of 8-bit UNORM, 1-2 codes on about a quarter of the pixels).
//! Each run renders four frames along a slow orbit (so reprojection, disocclusion and
//! accumulation all take part) and compares the final RGBA8 output.
//!
//! Tolerance: lavapipe is deterministic for a given shader binary, so the same code reproduces
//! every byte. A refactor may legitimately reorder floating-point operations (another shader
//! permutation mechanism, another evaluation order), which moves a channel by a code or two
//! after tonemapping. So each channel may differ by at most `common::MAX_CHANNEL_DIFF` codes, and
//! at most `common::MAX_CHANGED_FRACTION` of the pixels may differ at all; anything larger is a change
//! in behaviour, and the failure message names the image, the worst pixel and both values.
//!
//! Re-bless (only for an intended change of the image, stated in the commit):
//! `SSGI_BLESS_GOLDEN=1 cargo test --test golden`.

mod common;

use ssgi::renderer::config::Effects;
use ssgi::renderer::pcf::Pcf;
use ssgi::renderer::targets::Target;
use ssgi::renderer::{RenderConfig, Renderer};
use ssgi::scene::{load_scene, CameraPath, Orbit};
use std::path::{Path, PathBuf};

const SIZE: u32 = 64;
const FRAMES: u32 = 4;
/// The orbit's frame count: 1/240 of a turn (1.5 degrees) per frame.
const ORBIT_FRAMES: u32 = 240;

fn golden_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/golden")
}

/// Every non-empty combination of the three effects, named like `--effects`.
fn combinations() -> Vec<(String, Effects)> {
    let mut out = Vec::new();
    for bits in 1u32..8 {
        let e = Effects {
            direct: bits & 1 != 0,
            ao: bits & 2 != 0,
            indirect: bits & 4 != 0,
            ssdo: false,
        };
        let names: Vec<&str> = [("direct", e.direct), ("ao", e.ao), ("indirect", e.indirect)]
            .into_iter()
            .filter_map(|(n, on)| on.then_some(n))
            .collect();
        out.push((names.join("+"), e));
    }
    out
}

fn render(scene_spec: &str, effects: Effects, reuse: bool) -> Vec<u8> {
    let ctx = common::context();
    let scene = load_scene(scene_spec, None).unwrap_or_else(|e| {
        panic!(
            "golden scene {scene_spec:?} is missing: {e} (set SSGI_ASSETS to the shared \
             scenes directory, as tools/test does)"
        )
    });
    let mut config = RenderConfig {
        width: SIZE,
        height: SIZE,
        rsm_size: 128,
        effects,
        // The thesis's pairing: the accumulated 9-sample disc with reuse, the 7x7 grid without.
        pcf: if reuse { Pcf::NINE } else { Pcf::DEFAULT },
        ..Default::default()
    };
    config.temporal.reuse = reuse;
    let mut r = Renderer::new(&ctx, scene, config).expect("renderer");
    let base = r.scene.camera;
    // The goldens pin the renderer, not the scenes' orbits: a turn around the mesh from the
    // base camera, as `orbit` was when they were rendered.
    let around = Orbit::around(r.scene.mesh.bounds.center());
    for f in 0..FRAMES {
        // One turn per ORBIT_FRAMES seconds at 1 fps: frame f is f / ORBIT_FRAMES of a turn.
        let orbit = CameraPath::Orbit {
            seconds: ORBIT_FRAMES as f32,
        };
        let camera = orbit.camera_at(&base, &around, f as f32);
        r.render_frame(&camera).expect("frame");
    }
    r.finish().expect("finish");
    let out = r.read(Target::Output).expect("read output");
    common::assert_clean(&ctx);
    out.rgba8().expect("RGBA8 output")
}

fn check(scene_spec: &str, file_stem: &str) {
    let bless = std::env::var_os("SSGI_BLESS_GOLDEN").is_some();
    let mut failures = Vec::new();
    for (name, effects) in combinations() {
        for reuse in [true, false] {
            let file = golden_dir().join(format!(
                "{file_stem}-{name}-{}.png",
                if reuse { "reuse" } else { "noreuse" }
            ));
            let got = render(scene_spec, effects, reuse);
            if bless {
                std::fs::create_dir_all(golden_dir()).unwrap();
                image::save_buffer(&file, &got, SIZE, SIZE, image::ExtendedColorType::Rgba8)
                    .unwrap();
                continue;
            }
            let want = image::open(&file)
                .unwrap_or_else(|e| panic!("golden image {} missing: {e}", file.display()))
                .to_rgba8();
            assert_eq!(want.dimensions(), (SIZE, SIZE), "{}", file.display());
            if let Some(msg) = common::golden_compare(&got, want.as_raw(), SIZE) {
                failures.push(format!("{}: {msg}", file.display()));
            }
        }
    }
    assert!(
        failures.is_empty(),
        "golden mismatch:\n{}",
        failures.join("\n")
    );
}

#[test]
fn golden_cornell_box() {
    check("cornell-box", "cornell");
}

#[test]
fn golden_bunny_in_box() {
    check("box:bunny", "bunny");
}

#[test]
fn comparison_catches_a_changed_pixel() {
    let a = vec![10u8; 4 * 64 * 64];
    let mut b = a.clone();
    assert!(common::golden_compare(&a, &b, 64).is_none());
    b[4 * 100 + 1] = 10 + common::MAX_CHANNEL_DIFF + 1;
    let msg = common::golden_compare(&b, &a, 64).expect("a 4-code difference fails");
    assert!(msg.contains("(36, 1)"), "{msg}");
}
