//! The golden-image cases: what each image in `tests/golden/` renders, shared by the test
//! (tests/golden.rs, which compares) and the bless command (examples/bless_goldens.rs, the
//! only thing that writes them).

use ssgi::config::pcf::Pcf;
use ssgi::config::{AaMode, Effects, HistoryResample, IndirectFilter};
use ssgi::effects::ao::config::AoEstimator;
use ssgi::effects::ssdo::config::SsdoForm;
use ssgi::renderer::{RenderConfig, Renderer};
use ssgi::resources::targets::Target;
use ssgi::scene::{load_scene, CameraPath, Orbit};
use std::path::{Path, PathBuf};

/// The command that re-renders the goldens; the test names it and never writes an image.
pub const BLESS_COMMAND: &str = "cargo run --example bless_goldens";
/// The variable older versions of the test blessed with; the test now fails when it is set.
pub const BLESS_VARIABLE: &str = "SSGI_BLESS_GOLDEN";

pub const SIZE: u32 = 64;
/// Frames of the moving cases: the first at the orbit's start, three along it.
const MOVING_FRAMES: u32 = 4;
/// The orbit's frame count: 1/240 of a turn (1.5 degrees) per frame.
const ORBIT_FRAMES: u32 = 240;

/// The test that checks a case (tests run in parallel: the groups take similar times).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Group {
    /// Every combination of direct, AO and indirect light, moving, on the Cornell box.
    Cornell,
    /// The same on the bunny in a box.
    Bunny,
    /// AO, indirect light, SSDO's forms and SRAA, converged.
    Converged,
    /// The indirect filters, interleaving and the histories' resampling.
    Filters,
}

/// A golden image: a scene, a configuration and the frames leading to the compared one.
pub struct Case {
    /// File stem under `tests/golden/`.
    pub name: String,
    pub group: Group,
    scene: &'static str,
    config: RenderConfig,
    /// Frames held at the orbit's start (the first included) before moving.
    still: u32,
    /// Frames after those, each one orbit step further.
    moving: u32,
}

impl Case {
    pub fn path(&self) -> PathBuf {
        golden_dir().join(format!("{}.png", self.name))
    }
}

pub fn golden_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/golden")
}

/// Every golden case, in a fixed order.
pub fn cases() -> Vec<Case> {
    let mut out = combinations("cornell-box", "cornell", Group::Cornell);
    out.extend(combinations("box:bunny", "bunny", Group::Bunny));
    out.extend(converged_effects());
    out.extend(filters_and_resampling());
    out
}

/// The base configuration: 64x64, a 128x128 shadow map, the thesis's PCF for the reuse mode
/// (the accumulated 9-sample disc with reuse, the 7x7 grid without).
fn base(effects: Effects, reuse: bool) -> RenderConfig {
    let mut config = RenderConfig {
        width: SIZE,
        height: SIZE,
        rsm_size: 128,
        effects,
        pcf: if reuse { Pcf::NINE } else { Pcf::DEFAULT },
        ..Default::default()
    };
    config.temporal.reuse = reuse;
    config
}

/// Frames a static view takes to converge: every pattern of the rotation limit once, plus a
/// few for the refresh and the skip of unchanged frames to take part.
fn converged_frames(config: &RenderConfig) -> u32 {
    config.temporal.rotation_limit + 4
}

/// Every non-empty combination of direct, AO and indirect light with reuse on and off, along
/// the orbit: reprojection, disocclusion and accumulation all take part.
fn combinations(scene: &'static str, stem: &str, group: Group) -> Vec<Case> {
    let mut out = Vec::new();
    for bits in 1u32..8 {
        let effects = Effects {
            direct: bits & 1 != 0,
            ao: bits & 2 != 0,
            indirect: bits & 4 != 0,
            ..Effects::NONE
        };
        for reuse in [true, false] {
            let mode = if reuse { "reuse" } else { "noreuse" };
            out.push(Case {
                name: format!("{stem}-{}-{mode}", effects.to_string().replace(',', "+")),
                group,
                scene,
                config: base(effects, reuse),
                still: 1,
                moving: MOVING_FRAMES - 1,
            });
        }
    }
    out
}

/// A converged still view of the Cornell box named `cornell-converged-{variant}`.
fn converged(variant: &str, group: Group, config: RenderConfig) -> Case {
    Case {
        name: format!("cornell-converged-{variant}"),
        group,
        scene: "cornell-box",
        still: converged_frames(&config),
        moving: 0,
        config,
    }
}

/// The effects converged in a still view, alone where they can be, so that their own pixels are
/// compared (under the direct light AO moves a few codes): the thesis's AO and indirect light,
/// and the three with direct light (the default frame); ground-truth AO alone; SSDO's SSAO form alone, one-step SSDO
/// with the direct light its bounce sends; two-step SSDO, which its cache does not take, with
/// direct light and without reuse along the orbit; SRAA and shadow-aware SRAA on every effect.
fn converged_effects() -> Vec<Case> {
    let ao = Effects {
        ao: true,
        ..Effects::NONE
    };
    let indirect = Effects {
        indirect: true,
        ..Effects::NONE
    };
    let ssdo = Effects {
        ssdo: true,
        ..Effects::NONE
    };
    let lit_ssdo = Effects {
        direct: true,
        ..ssdo
    };
    let mut ssao_form = base(ssdo, true);
    ssao_form.ssdo.form = SsdoForm::Ssao;
    let mut two_step = base(lit_ssdo, false);
    two_step.ssdo.form = SsdoForm::TwoStep;
    let mut gtao = base(ao, true);
    gtao.ao.estimator = AoEstimator::Gtao;
    let all = base(Effects::ALL, true);
    let aa = |mode| {
        let mut c = all;
        c.aa.mode = mode;
        c
    };
    let group = Group::Converged;
    vec![
        converged("direct+ao+indirect", group, all),
        converged("ao", group, base(ao, true)),
        converged("ao-gtao", group, gtao),
        converged("indirect", group, base(indirect, true)),
        converged("direct+ssdo", group, base(lit_ssdo, true)),
        converged("ssdo-ssao", group, ssao_form),
        Case {
            name: "cornell-direct+ssdo-two-step-noreuse".into(),
            group,
            scene: "cornell-box",
            config: two_step,
            still: 1,
            moving: MOVING_FRAMES - 1,
        },
        converged("sraa", group, aa(AaMode::Sraa)),
        converged("sraa-shadow", group, aa(AaMode::SraaShadow)),
    ]
}

/// Converged in a still view: indirect light alone filtered per frame by CCIPCA and by the
/// two joint bilateral filters, and gathered interleaved in 2x2 blocks. Then a converged view
/// of every effect that moves, its histories resampled bilinearly (the default) or from the
/// nearest point.
fn filters_and_resampling() -> Vec<Case> {
    let group = Group::Filters;
    let indirect = base(
        Effects {
            indirect: true,
            ..Effects::NONE
        },
        true,
    );
    let filtered = |filter| {
        let mut c = indirect;
        c.indirect.filter = filter;
        c
    };
    let mut interleaved = indirect;
    interleaved.indirect.interleave = 2;
    let all = base(Effects::ALL, true);
    let moved = |name: &str, resample| {
        let mut config = all;
        config.temporal.resample = resample;
        Case {
            name: format!("cornell-converged-moved-{name}"),
            group,
            scene: "cornell-box",
            still: converged_frames(&config),
            moving: MOVING_FRAMES - 1,
            config,
        }
    };
    vec![
        converged("indirect-ccipca", group, filtered(IndirectFilter::Ccipca)),
        converged("indirect-jbf11", group, filtered(IndirectFilter::Jbf11)),
        converged("indirect-jbf17", group, filtered(IndirectFilter::Jbf17)),
        converged("indirect-svgf", group, filtered(IndirectFilter::Svgf)),
        converged("indirect-interleave2", group, interleaved),
        moved("bilinear", HistoryResample::Bilinear),
        moved("point", HistoryResample::Point),
    ]
}

/// Render `case` under validation and return its final RGBA8 output.
pub fn render(case: &Case) -> Vec<u8> {
    let ctx = super::context();
    let scene = load_scene(case.scene, None).unwrap_or_else(|e| {
        panic!(
            "golden scene {:?} is missing: {e} (set SSGI_ASSETS to the shared scenes directory, \
             as tools/test does)",
            case.scene
        )
    });
    let mut r = Renderer::new(&ctx, scene, case.config).expect("renderer");
    let base = r.scene.camera;
    // The goldens pin the renderer, not the scenes' orbits: a turn around the mesh from the
    // base camera, as `orbit` was when they were first rendered.
    let around = Orbit::around(r.scene.mesh.bounds.center());
    // One turn per ORBIT_FRAMES seconds at 1 fps: step s is s / ORBIT_FRAMES of a turn.
    let orbit = CameraPath::Orbit {
        seconds: ORBIT_FRAMES as f32,
    };
    let steps = std::iter::repeat_n(0, case.still as usize).chain(1..=case.moving);
    for step in steps {
        let camera = orbit.camera_at(&base, &around, step as f32);
        r.render_frame(&camera).expect("frame");
    }
    r.finish().expect("finish");
    let out = r.read(Target::Output).expect("read output");
    super::assert_clean(&ctx);
    out.rgba8().expect("RGBA8 output")
}
