//! The dependency table comes from the passes' declarations: each pass's own inputs
//! (`PassId::inputs`) must be the frame-block members its compute shaders name (camera or
//! light), and what the table derives through the resource declarations must hold for the
//! cases a reader can check by hand. No GPU needed.

use ssgi::effects::REGISTRY;
use ssgi::passes::{Change, PassId};
use ssgi::renderer::all_layouts;
use ssgi::renderer::catalog::frame_layouts;
use ssgi::renderer::dependencies::{derive, Changes};
use ssgi::shaders::ShaderStage;
use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// Frame-block members (shaders/include/frame.glsl) that are the camera's.
const CAMERA: &[&str] = &["view_proj", "prev_view_proj", "camera_pos", "tan_half_fov"];
/// Frame-block members that are the lights' (the spot's and the ambient radiance).
const LIGHT: &[&str] = &[
    "light_view_proj",
    "light_pos",
    "light_cos_outer",
    "light_dir",
    "light_cos_inner",
    "light_intensity",
    "light_near",
    "light_far",
    "light_tan_half_fov",
    "shadow_map_size",
    "ambient",
];

fn shaders() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("shaders")
}

/// A shader's text with its includes (but the frame block's declaration), comments removed.
fn expanded(path: &Path, seen: &mut BTreeSet<std::path::PathBuf>, out: &mut String) {
    if path.ends_with("frame.glsl") || !seen.insert(path.to_path_buf()) {
        return;
    }
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{path:?}: {e}"));
    for line in text.lines() {
        let code = line.split("//").next().unwrap_or("");
        if let Some(rest) = code.trim().strip_prefix("#include \"") {
            // As build.rs resolves it: the shader's own folder first, then shaders/include.
            let name = rest.trim_end_matches('"');
            let own = path.parent().map(|d| d.join(name));
            let header = own
                .filter(|p| p.exists())
                .unwrap_or_else(|| shaders().join("include").join(name));
            expanded(&header, seen, out);
        } else {
            out.push_str(code);
            out.push('\n');
        }
    }
}

fn names(text: &str, member: &str) -> bool {
    text.match_indices(member).any(|(i, _)| {
        let before = text[..i].chars().next_back();
        let after = text[i + member.len()..].chars().next();
        let word = |c: Option<char>| c.is_some_and(|c| c.is_alphanumeric() || c == '_');
        !word(before) && !word(after)
    })
}

#[test]
fn the_listed_members_are_the_frame_blocks() {
    let frame = std::fs::read_to_string(shaders().join("include/frame.glsl")).unwrap();
    for m in CAMERA.iter().chain(LIGHT) {
        assert!(names(&frame, m), "frame.glsl has no member {m}");
    }
}

/// For every compute pass: the camera and light it declares are exactly those its shaders
/// name (over every pipeline of the pass; includes count, as the textual check cannot see
/// which permutation calls what).
#[test]
fn declared_inputs_match_what_the_compute_shaders_read() {
    let mut named: BTreeMap<&str, (PassId, BTreeSet<Change>)> = BTreeMap::new();
    for layout in all_layouts() {
        for m in &layout.modules {
            if m.stage != ShaderStage::Compute {
                continue;
            }
            let mut text = String::new();
            expanded(&shaders().join(m.name), &mut BTreeSet::new(), &mut text);
            let entry = named
                .entry(layout.pass.name())
                .or_insert((layout.pass, BTreeSet::new()));
            if CAMERA.iter().any(|c| names(&text, c)) {
                entry.1.insert(Change::Camera);
            }
            if LIGHT.iter().any(|c| names(&text, c)) {
                entry.1.insert(Change::Light);
            }
        }
    }
    assert!(named.len() > 20, "only {} compute passes", named.len());
    let mut wrong = Vec::new();
    for (name, (pass, seen)) in &named {
        let declared: BTreeSet<Change> = pass
            .inputs()
            .iter()
            .copied()
            .filter(|c| matches!(c, Change::Camera | Change::Light))
            .collect();
        if &declared != seen {
            wrong.push(format!(
                "{name}: declares {declared:?}, its shaders read {seen:?}"
            ));
        }
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}

/// What the table derives: raster passes read only what they draw from; an effect depends on
/// the light exactly when one of its passes reads it or reads what the light view or another
/// lit pass wrote (AO and the normals debug effect do not); everything an effect writes reaches the composite.
#[test]
fn derived_changes_follow_the_resources() {
    let effects: Vec<_> = REGISTRY.iter().map(|r| (r.layouts)()).collect();
    let d = derive(&frame_layouts(), &effects);
    let set = |c: &[Change]| Changes::of(c);
    use Change::*;
    assert_eq!(d.pass(PassId::LIGHT_VIEW), set(&[Light, Object]));
    assert_eq!(d.pass(PassId::GBUFFER), set(&[Camera, Object]));
    assert_eq!(
        d.pass(ssgi::post::sraa::pass::SRAA_GEOMETRY),
        set(&[Camera, Object])
    );
    for (r, changes) in REGISTRY.iter().zip(&d.effects) {
        // AO and the normals debug effect read nothing of the light, directly or through
        // their sources.
        let lit = r.id != ssgi::effects::ao::ID && r.id != ssgi::effects::normals::ID;
        assert_eq!(
            changes.contains(Light),
            lit,
            "{:?}: {:?}",
            r.id,
            changes.list()
        );
        for c in [Camera, Object, Config] {
            assert!(changes.contains(c), "{:?} misses {c:?}", r.id);
        }
    }
    // The AO's blur reads nothing of the light, directly or through its sources.
    assert!(!d.pass(ssgi::effects::ao::pass::BLUR).contains(Light));
    // SSDO's blur reads the SSDO result, which reads the direct light.
    assert!(d
        .pass(ssgi::effects::ssdo::pass::SSDO_BILATERAL)
        .contains(Light));
    let everything = set(&Change::ALL);
    assert_eq!(d.pass(PassId::COMPOSITE), everything);
    assert_eq!(d.pass(ssgi::post::sraa::pass::SRAA), everything);
    // Only AO: the reprojection still declares the light (the shadow lane's reach).
    let ao_only = derive(&frame_layouts(), &[(REGISTRY[1].layouts)()]);
    assert_eq!(REGISTRY[1].id, ssgi::effects::ao::ID);
    assert!(!ao_only.effects[0].contains(Light));
}
