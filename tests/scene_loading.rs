//! Scene loading end to end: malformed OBJ fixtures, materials and textures, the real
//! benchmark assets (when SSGI_ASSETS is set), camera/light conventions, ray queries and
//! camera path files.

use glam::{Vec3, Vec4Swizzles};
use ssgi::scene::{
    load_obj, load_scene, pixel_to_ndc, CameraPath, LightPath, Mesh, Orbit, SceneError, SpotLight,
};
use std::path::{Path, PathBuf};
use std::sync::Arc;

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures")
        .join(name)
}

fn load_err(name: &str) -> SceneError {
    match load_obj(&fixture(name)) {
        Ok(m) => panic!(
            "{name} loaded ({} triangles) but should fail",
            m.triangle_count()
        ),
        Err(e) => e,
    }
}

/// The message names the file and the line, compiler style.
fn assert_names_line(e: &SceneError, file: &str, line: usize) {
    let msg = e.to_string();
    assert!(
        msg.contains(&format!("{file}:{line}:")),
        "'{msg}' lacks {file}:{line}:"
    );
}

/// A fresh directory under the system temp dir, removed on drop.
struct TempDir(PathBuf);

impl TempDir {
    fn new(tag: &str) -> Self {
        let dir = std::env::temp_dir().join(format!("ssgi-{tag}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        Self(dir)
    }

    fn write(&self, name: &str, text: &str) -> PathBuf {
        let p = self.0.join(name);
        std::fs::write(&p, text).unwrap();
        p
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

// ---------------------------------------------------------------- malformed OBJ files

#[test]
fn nan_vertex_message_is_exact() {
    // Relative path, as a user would type it (tests run in the package root).
    let Err(e) = load_scene("tests/fixtures/nan_vertex.obj", None) else {
        panic!("loaded a NaN vertex");
    };
    assert!(matches!(e, SceneError::NonFinite { line: 3, .. }));
    assert_eq!(
        e.to_string(),
        "tests/fixtures/nan_vertex.obj:3: non-finite coordinate in vertex 'v 0 nan 0'"
    );
}

#[test]
fn inf_vertex() {
    let e = load_err("inf_vertex.obj");
    assert!(
        matches!(
            e,
            SceneError::NonFinite {
                kind: "vertex",
                line: 4,
                ..
            }
        ),
        "{e}"
    );
    assert_names_line(&e, "inf_vertex.obj", 4);
}

#[test]
fn bad_number() {
    let e = load_err("bad_number.obj");
    assert!(
        matches!(
            e,
            SceneError::BadNumber {
                kind: "normal",
                line: 6,
                ..
            }
        ),
        "{e}"
    );
    assert_names_line(&e, "bad_number.obj", 6);
    assert!(e.to_string().contains("'0.5x'"), "{e}");
}

#[test]
fn index_out_of_range() {
    let e = load_err("index_out_of_range.obj");
    assert!(
        matches!(
            e,
            SceneError::IndexOutOfRange {
                index: 4,
                count: 3,
                line: 6,
                ..
            }
        ),
        "{e}"
    );
    assert_names_line(&e, "index_out_of_range.obj", 6);
}

#[test]
fn negative_index_out_of_range() {
    let e = load_err("negative_index_out_of_range.obj");
    assert!(
        matches!(
            e,
            SceneError::IndexOutOfRange {
                index: -4,
                count: 3,
                line: 6,
                ..
            }
        ),
        "{e}"
    );
    assert_names_line(&e, "negative_index_out_of_range.obj", 6);
}

#[test]
fn empty_file_has_no_faces() {
    let e = load_err("empty.obj");
    assert!(matches!(e, SceneError::EmptyMesh { .. }), "{e}");
    assert!(e.to_string().contains("empty.obj"), "{e}");
}

#[test]
fn huge_coordinate() {
    let e = load_err("huge_coord.obj");
    assert!(
        matches!(e, SceneError::HugeCoordinate { line: 4, .. }),
        "{e}"
    );
    assert_names_line(&e, "huge_coord.obj", 4);
    assert!(e.to_string().contains("huge coordinate"), "{e}");
}

#[test]
fn malformed_face_among_good_ones() {
    let e = load_err("two_faces_one_bad_line.obj");
    assert!(matches!(e, SceneError::Syntax { line: 7, .. }), "{e}");
    assert_names_line(&e, "two_faces_one_bad_line.obj", 7);
    assert!(e.to_string().contains("'x'"), "{e}");
}

#[test]
fn face_with_two_vertices() {
    let e = load_err("too_few_vertices.obj");
    assert!(
        matches!(
            e,
            SceneError::TooFewVertices {
                count: 2,
                line: 6,
                ..
            }
        ),
        "{e}"
    );
    assert_names_line(&e, "too_few_vertices.obj", 6);
}

#[test]
fn missing_file_names_the_path() {
    let e = load_scene("tests/fixtures/does_not_exist.obj", None)
        .err()
        .unwrap();
    assert!(matches!(e, SceneError::Io { .. }), "{e}");
    assert!(
        e.to_string().contains("tests/fixtures/does_not_exist.obj"),
        "{e}"
    );
}

#[test]
fn non_utf8_bytes_are_a_warning_not_an_error() {
    let dir = TempDir::new("latin1");
    let p = dir.0.join("latin1.obj");
    let mut bytes = b"# caf\xe9 in Latin-1\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n".to_vec();
    bytes.splice(0..0, [0xef, 0xbb, 0xbf]); // and a UTF-8 BOM in front
    std::fs::write(&p, bytes).unwrap();
    let m = load_obj(&p).unwrap();
    assert_eq!(m.triangle_count(), 1);
    assert!(m.stats.warnings.iter().any(|w| w.contains("UTF-8")));
}

// ---------------------------------------------------------------- geometry and materials

#[test]
fn degenerate_triangle_is_dropped_and_counted() {
    let m = load_obj(&fixture("degenerate.obj")).unwrap();
    assert_eq!(m.triangle_count(), 1);
    assert_eq!(m.stats.triangles, 2);
    assert_eq!(m.stats.faces, 2);
    assert_eq!(m.stats.dropped_zero_area, 1);
    assert_eq!(m.stats.dropped_slivers, 0);
    // Bounds cover only what is drawn: the dropped triangle's far vertex (2, 0, 0) is out.
    assert_eq!(m.bounds.max, Vec3::new(1.0, 1.0, 0.0));
}

#[test]
fn tiny_valid_triangles_are_kept_and_slivers_counted_apart() {
    let m = load_obj(&fixture("tiny_triangles.obj")).unwrap();
    assert_eq!(m.stats.triangles, 4);
    assert_eq!(m.stats.dropped_zero_area, 1);
    assert_eq!(m.stats.dropped_slivers, 1);
    assert_eq!(
        m.triangle_count(),
        2,
        "the 1e-4 triangle of a 1000-unit model is drawn"
    );
    let tiny = (0..m.triangle_count())
        .map(|t| m.triangle(t))
        .find(|[a, b, _]| (*b - *a).length() < 1e-3)
        .expect("the tiny triangle");
    assert_eq!(tiny[0], Vec3::new(10.0, 10.0, 0.0));
}

#[test]
fn polygons_are_fan_triangulated() {
    let m = load_obj(&fixture("polygons.obj")).unwrap();
    assert_eq!(
        (m.stats.faces, m.stats.triangles, m.triangle_count()),
        (2, 5, 5)
    );
    // No normals in the file: computed ones face +z for this planar data.
    assert!(m
        .vertices
        .iter()
        .all(|v| Vec3::from(v.normal).abs_diff_eq(Vec3::Z, 1e-6)));
    assert_eq!(m.materials.len(), 1);
    assert_eq!(m.materials[0].diffuse, [0.8; 3]);
}

#[test]
fn file_normals_are_normalised_and_zero_ones_replaced() {
    let m = load_obj(&fixture("normals.obj")).unwrap();
    for v in &m.vertices {
        assert!(
            Vec3::from(v.normal).abs_diff_eq(Vec3::Z, 1e-6),
            "{:?}",
            v.normal
        );
    }
}

#[test]
fn materials_group_draw_ranges() {
    let m = load_obj(&fixture("two_materials.obj")).unwrap();
    let names: Vec<_> = m.materials.iter().map(|x| x.name.as_str()).collect();
    assert_eq!(names, ["red", "blue"], "unused materials are dropped");
    assert_eq!(m.triangle_count(), 3);
    let count = |name: &str| {
        m.ranges
            .iter()
            .filter(|r| m.materials[r.material].name == name)
            .map(|r| r.index_count)
            .sum::<u32>()
    };
    assert_eq!((count("red"), count("blue")), (6, 3));
    assert_eq!(m.ranges.len(), 2, "one range per material");
    // Ranges tile the index buffer.
    let mut next = 0;
    for r in &m.ranges {
        assert_eq!(r.first_index, next);
        next += r.index_count;
    }
    assert_eq!(next as usize, m.indices.len());
    // The `l` line is not turned into a triangle, but it is reported.
    assert!(m.stats.warnings.iter().any(|w| w.contains("line element")));
}

#[test]
fn missing_texture_falls_back_to_colour_with_warning() {
    let m = load_obj(&fixture("missing_texture.obj")).unwrap();
    assert_eq!(m.materials.len(), 1);
    assert_eq!(m.materials[0].diffuse, [0.5, 0.25, 0.125]);
    assert!(m.materials[0].diffuse_texture.is_none());
    let w = m.stats.warnings.join("\n");
    assert!(
        w.contains("no_such_texture.png") && w.contains("brick"),
        "{w}"
    );
}

#[test]
fn missing_mtl_uses_default_material_with_warning() {
    let m = load_obj(&fixture("missing_mtl.obj")).unwrap();
    assert_eq!(m.materials[0].diffuse, [0.8; 3]);
    let w = m.stats.warnings.join("\n");
    assert!(w.contains("no_such_library.mtl"), "{w}");
    assert!(w.contains("ghost"), "{w}");
}

#[test]
fn malformed_mtl_is_a_warning_with_its_line() {
    let m = load_obj(&fixture("bad_kd.obj")).unwrap();
    assert_eq!(m.materials[0].diffuse, [0.8; 3]);
    let w = m.stats.warnings.join("\n");
    assert!(w.contains("bad_kd.mtl:2:"), "{w}");
}

#[test]
fn textures_decode_once_and_uv_v_is_flipped() {
    let dir = TempDir::new("textures");
    // 2×2 PNG: top row red, bottom row blue.
    let img = image::RgbaImage::from_fn(2, 2, |_, y| {
        if y == 0 {
            image::Rgba([255, 0, 0, 255])
        } else {
            image::Rgba([0, 0, 255, 255])
        }
    });
    img.save(dir.0.join("shared.png")).unwrap();
    std::fs::create_dir_all(dir.0.join("mtl")).unwrap();
    // Textures resolve relative to the MTL's own directory, with case-insensitive fallback.
    std::fs::rename(dir.0.join("shared.png"), dir.0.join("mtl/Shared.PNG")).unwrap();
    dir.write(
        "mtl/lib.mtl",
        "newmtl a\nKd 1 1 1\nmap_Kd shared.png\nnewmtl b\nKd 1 1 1\nmap_Kd -bm 1 shared.png\n",
    );
    let obj = dir.write(
        "model.obj",
        "mtllib mtl/lib.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n\
         usemtl a\nf 1/1 2/2 3/3\nusemtl b\nf 1/1 3/3 2/2\n",
    );
    let m = load_obj(&obj).unwrap();
    assert!(m.stats.warnings.is_empty(), "{:?}", m.stats.warnings);
    let ta = m.materials[0].diffuse_texture.clone().unwrap();
    let tb = m.materials[1].diffuse_texture.clone().unwrap();
    assert!(Arc::ptr_eq(&ta, &tb), "one decode for a texture used twice");
    assert_eq!((ta.width, ta.height, ta.rgba8.len()), (2, 2, 16));
    assert_eq!(
        &ta.rgba8[..4],
        &[255, 0, 0, 255],
        "row 0 is the top of the image"
    );
    // vt (0, 1) is the top of the image in OBJ; stored as uv (0, 0).
    let top = m
        .vertices
        .iter()
        .find(|v| v.position == [0.0, 1.0, 0.0])
        .unwrap();
    assert_eq!(top.uv, [0.0, 0.0]);
    assert!(m.has_textures());
}

// ---------------------------------------------------------------- scene specs

#[test]
fn unknown_scene_lists_builtins_and_how_to_set_assets() {
    let e = load_scene("no-such-scene", Some(Path::new("/definitely/not/here"))).unwrap_err();
    assert!(matches!(e, SceneError::UnknownScene { .. }), "{e}");
    let msg = e.to_string();
    for needle in [
        "no-such-scene",
        "cornell-box",
        "pyramids",
        "/definitely/not/here",
        "--assets",
    ] {
        assert!(msg.contains(needle), "'{needle}' missing from: {msg}");
    }
}

#[test]
fn asset_folder_with_two_objs_is_ambiguous() {
    let dir = TempDir::new("ambiguous");
    std::fs::create_dir_all(dir.0.join("pair")).unwrap();
    let tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    dir.write("pair/one.obj", tri);
    dir.write("pair/two.obj", tri);
    std::fs::create_dir_all(dir.0.join("single")).unwrap();
    dir.write("single/only.obj", tri);

    let e = load_scene("pair", Some(&dir.0)).unwrap_err();
    assert!(matches!(e, SceneError::AmbiguousAsset { .. }), "{e}");
    let msg = e.to_string();
    assert!(msg.contains("one.obj") && msg.contains("two.obj"), "{msg}");

    let s = load_scene("single", Some(&dir.0)).unwrap();
    assert_eq!(s.name, "only");
    let s = load_scene("box:single", Some(&dir.0)).unwrap();
    assert_eq!(s.name, "box:only");
    let e = load_scene("nothing", Some(&dir.0)).unwrap_err().to_string();
    assert!(
        e.contains("pair") && e.contains("single"),
        "lists available assets: {e}"
    );
}

#[test]
fn cornell_box_defaults() {
    let s = load_scene("cornell-box", None).unwrap();
    assert_eq!(s.camera.position, Vec3::new(0.0, 1.0, 3.4));
    assert_eq!(s.camera.vfov_deg, 40.0);
    assert_eq!(s.light.position, Vec3::new(0.0, 1.95, -0.03));
    assert_eq!(s.light.intensity, Vec3::new(6.0, 5.2, 4.2));
    assert_eq!(s.ambient, Vec3::splat(0.03));
}

// ---------------------------------------------------------------- real assets

/// The asset directory; a test that needs it fails (never skips) when SSGI_ASSETS is not set.
fn assets() -> PathBuf {
    ssgi::scene::asset_dir_from_env().unwrap_or_else(|| panic!("SSGI_ASSETS is not set: this test needs the papers' models (the shared scenes directory, ../shared/scenes in this workspace); tools/test sets it"))
}

/// The asset's mesh as loaded (without the ground a single model's scene adds).
fn load_asset(name: &str, dir: &Path) -> Mesh {
    match ssgi::scene::load_model(name, Some(dir)) {
        Ok((_, m)) => m,
        Err(e) => panic!("asset {name} from {}: {e}", dir.display()),
    }
}

#[test]
fn asset_face_counts_match_sources_md() {
    let dir = assets();
    // Face counts from shared/scenes/SOURCES.md (all-triangle files: faces = triangles).
    for (name, faces) in [
        ("bunny", 69_451),
        ("sponza", 66_454),
        ("venus", 43_357),
        ("buddha", 100_000),
        ("dragon", 100_000),
        ("sibenik", 75_284),
    ] {
        let m = load_asset(name, &dir);
        assert_eq!(m.stats.faces, faces, "{name} faces");
        assert_eq!(m.stats.triangles, faces, "{name} triangles");
        assert_eq!(
            m.triangle_count() + m.stats.dropped(),
            faces,
            "{name}: drawn + dropped"
        );
        assert!(m.bounds.diagonal() > 0.0);
        assert!(m
            .vertices
            .iter()
            .all(|v| Vec3::from(v.normal).is_normalized()));
    }
}

#[test]
fn conference_loads() {
    let dir = assets();
    let m = load_asset("conference", &dir);
    assert_eq!(m.stats.triangles, 331_179);
}

/// The loader drops exactly the triangles docs/scenes.md's rule names, counted here from tobj's
/// own triangulation: zero area in f64 (53,627 in conference), or a height under f32 epsilon
/// times the longest edge.
#[test]
fn conference_drops_only_degenerate_triangles() {
    let dir = assets();
    let path = ssgi::scene::resolve_model("conference", Some(&dir)).unwrap();
    let (models, _) = tobj::load_obj(&path, &tobj::GPU_LOAD_OPTIONS).unwrap();
    let (mut zero, mut slivers) = (0, 0);
    for model in &models {
        let p = |i: u32| {
            let k = 3 * i as usize;
            let v = &model.mesh.positions[k..k + 3];
            glam::DVec3::new(v[0] as f64, v[1] as f64, v[2] as f64)
        };
        for t in model.mesh.indices.chunks_exact(3) {
            let [a, b, c] = [p(t[0]), p(t[1]), p(t[2])];
            let twice_area = (b - a).cross(c - a).length();
            let longest = (b - a).length().max((c - b).length()).max((a - c).length());
            if twice_area == 0.0 {
                zero += 1;
            } else if twice_area / longest < f32::EPSILON as f64 * longest {
                slivers += 1;
            }
        }
    }
    assert_eq!(zero, 53_627, "zero-area triangles counted from the file");
    let m = load_asset("conference", &dir);
    assert_eq!(m.stats.dropped_zero_area, zero);
    assert_eq!(m.stats.dropped_slivers, slivers);
    assert_eq!(m.triangle_count(), 331_179 - zero - slivers);
}

#[test]
fn cornell_box_obj_quads_with_relative_indices() {
    let dir = assets();
    let s = load_scene("cornell-box/CornellBox-Original.obj", Some(&dir)).unwrap();
    assert_eq!(s.mesh.stats.faces, 18);
    assert_eq!(s.mesh.stats.triangles, 36);
    assert!(s.mesh.materials.iter().any(|m| m.name == "leftWall"));
}

#[test]
fn sponza_materials_and_textures() {
    let dir = assets();
    let m = load_asset("sponza", &dir);
    assert!(m.stats.warnings.is_empty(), "{:#?}", m.stats.warnings);
    assert_eq!(m.materials.len(), 20);
    assert!(m.materials.iter().all(|x| x.diffuse_texture.is_some()));
    // Distinct decoded textures = distinct map_Kd files in the MTL.
    let mtl = std::fs::read_to_string(dir.join("sponza/sponza.mtl")).unwrap();
    let mut files: Vec<&str> = mtl
        .lines()
        .filter_map(|l| l.trim().strip_prefix("map_Kd "))
        .map(str::trim)
        .collect();
    files.sort();
    files.dedup();
    let mut arcs: Vec<_> = m
        .materials
        .iter()
        .filter_map(|x| x.diffuse_texture.as_ref().map(Arc::as_ptr))
        .collect();
    arcs.sort();
    arcs.dedup();
    assert_eq!(arcs.len(), files.len());
    assert!(m.vertices.iter().any(|v| v.uv != [0.0, 0.0]));
}

#[test]
fn bunny_in_a_box() {
    let dir = assets();
    let s = load_scene("box:bunny", Some(&dir)).unwrap();
    assert_eq!(s.name, "box:stanford-bunny");
    // The model is centred on the floor, ~0.9 m tall, inside the 2 m room.
    let ray_down = s
        .mesh
        .raycast(Vec3::new(0.0, 1.9, 0.0), Vec3::NEG_Y, 2.0)
        .unwrap();
    assert!(
        ray_down.position.y > 0.05 && ray_down.position.y < 0.95,
        "{ray_down:?}"
    );
    assert!(s.mesh.bounds.max.y <= 2.0 + 1e-5 && s.mesh.bounds.min.y >= -1e-6);
}

// ---------------------------------------------------------------- camera and light

#[test]
fn camera_rays_project_back_to_their_pixels() {
    let cam = load_scene("cornell-box", None).unwrap().camera;
    let (w, h) = (64u32, 48u32);
    let aspect = w as f32 / h as f32;
    let vp = cam.view_proj(aspect);
    for (px, py) in [(0, 0), (63, 0), (0, 47), (31, 23), (50, 10)] {
        let (nx, ny) = pixel_to_ndc(px as f32, py as f32, w, h);
        let (o, d) = cam.ray(nx, ny, aspect);
        assert!(d.is_normalized());
        for t in [0.5, 2.0, 10.0] {
            let clip = vp * (o + d * t).extend(1.0);
            let ndc = clip.xyz() / clip.w;
            assert!(
                (ndc.x - nx).abs() < 1e-5 && (ndc.y - ny).abs() < 1e-5,
                "{ndc}"
            );
            assert!(ndc.z > 0.0 && ndc.z < 1.0);
        }
    }
    // Y flip: the top-left pixel's ray goes up and left.
    let (nx, ny) = pixel_to_ndc(0.0, 0.0, w, h);
    let (_, d) = cam.ray(nx, ny, aspect);
    assert!(d.y > 0.0 && d.x < 0.0, "{d}");
    assert!(cam.proj(aspect).y_axis.y < 0.0);
}

#[test]
fn spot_light_inverse_square_on_axis() {
    let light: SpotLight = load_scene("cornell-box", None).unwrap().light;
    for d in [0.25f32, 1.0, 1.95] {
        let p = light.position + light.direction * d;
        let e = light.irradiance(p, -light.direction);
        assert!(
            e.abs_diff_eq(light.intensity / (d * d), 1e-4 * e.max_element()),
            "{e}"
        );
    }
}

#[test]
fn raycasts_in_the_cornell_box() {
    let s = load_scene("cornell-box", None).unwrap();
    let (o, d) = s.camera.ray(0.0, 0.0, 1.0);
    let hit = s.mesh.raycast(o, d, 100.0).unwrap();
    // The centre ray (x = 0, y = 1) meets the tall box's front face, the edge from
    // (-0.53, 0.09) to (0.04, -0.09) in (x, z): at x = 0, z = 0.09 - 0.18 * 0.53 / 0.57.
    let z = 0.09 - 0.18 * 0.53 / 0.57;
    assert!(
        hit.position.abs_diff_eq(Vec3::new(0.0, 1.0, z), 1e-5),
        "{hit:?}"
    );
    assert!((hit.t - (s.camera.position.z - z)).abs() < 1e-5);
    assert!(hit.normal.z > 0.9 && hit.normal.dot(d) < 0.0);

    let down = s
        .mesh
        .raycast(Vec3::new(-0.5, 1.5, 0.6), Vec3::NEG_Y, 10.0)
        .unwrap();
    assert!(
        down.position.abs_diff_eq(Vec3::new(-0.5, 0.0, 0.6), 1e-6),
        "{down:?}"
    );
    assert_eq!(down.normal, Vec3::Y);

    // The floor under the tall box is hidden from the light; the open floor is not.
    let light = s.light.position;
    assert!(s.mesh.occluded(Vec3::new(-0.3, 0.0, -0.3), light));
    assert!(!s.mesh.occluded(Vec3::new(-0.5, 0.0, 0.6), light));
}

// ---------------------------------------------------------------- camera paths

const JSON_KEYS: &str = r#"{"keyframes": [
    {"time": 0.0, "position": [0, 1, 3], "target": [0, 1, 0]},
    {"time": 2.0, "position": [2, 1, 3], "target": [0, 1, 0]}
]}"#;

const TOML_KEYS: &str = r#"
[[keyframes]]
time = 0.0
position = [0.0, 1.0, 3.0]
target = [0.0, 1.0, 0.0]

[[keyframes]]
time = 2.0
position = [2.0, 1.0, 3.0]
target = [0.0, 1.0, 0.0]
"#;

#[test]
fn keyframe_files_parse_and_interpolate() {
    let dir = TempDir::new("paths");
    let base = load_scene("cornell-box", None).unwrap();
    for (name, text) in [("path.json", JSON_KEYS), ("path.toml", TOML_KEYS)] {
        let file = dir.write(name, text);
        let path = CameraPath::parse(file.to_str().unwrap()).unwrap();
        // Keyframe times are seconds.
        let at = |t| path.camera_at(&base.camera, &base.orbit(), t);
        assert_eq!(at(0.0).position, Vec3::new(0.0, 1.0, 3.0));
        assert!(
            at(1.0).position.abs_diff_eq(Vec3::new(1.0, 1.0, 3.0), 1e-6),
            "{name}"
        );
        assert_eq!(at(2.0).position, Vec3::new(2.0, 1.0, 3.0));
        assert_eq!(
            at(5.0).position,
            Vec3::new(2.0, 1.0, 3.0),
            "held at the end"
        );
        assert_eq!(at(1.5).vfov_deg, base.camera.vfov_deg);
        assert_eq!(path.name(), "keyframes(2)");
    }
}

#[test]
fn bad_keyframe_files_name_the_path() {
    let dir = TempDir::new("badpaths");
    let cases = [
        ("syntax.json", r#"{"keyframes": [ {"time": 0.0, "#),
        (
            "missing_field.json",
            r#"{"keyframes": [{"time": 0.0, "position": [0, 0, 0]}]}"#,
        ),
        ("empty.toml", "keyframes = []\n"),
        (
            "backwards.json",
            r#"{"keyframes": [
                {"time": 1.0, "position": [0, 0, 0], "target": [0, 0, -1]},
                {"time": 0.0, "position": [0, 0, 0], "target": [0, 0, -1]}]}"#,
        ),
        ("wrong_type.toml", "[[keyframes]]\ntime = \"soon\"\n"),
    ];
    for (name, text) in cases {
        let file = dir.write(name, text);
        let e = CameraPath::parse(file.to_str().unwrap()).unwrap_err();
        assert!(matches!(e, SceneError::CameraPath { .. }), "{name}: {e}");
        assert!(e.to_string().contains(name), "{name}: {e}");
    }
    let e = CameraPath::parse("/no/such/path.json")
        .unwrap_err()
        .to_string();
    assert!(e.contains("/no/such/path.json"), "{e}");
}

/// Issue 62 items 10 and 17: a keyframe whose target is its position (the camera would look
/// down -z silently) or with a NaN is refused, in a camera or light path file, naming the
/// keyframe and key, with its line in TOML, as a scene file's keyframes are.
#[test]
fn bad_keyframes_name_the_keyframe_key_and_line() {
    let dir = TempDir::new("keyframe-keys");
    let toml_keys = |second: &str| {
        format!(
            "[[keyframes]]\ntime = 0\nposition = [0, 1, 3]\ntarget = [0, 1, 0]\n\n\
             [[keyframes]]\ntime = 1\n{second}\n"
        )
    };
    let cases = [
        (
            "same.toml",
            toml_keys("position = [0, 1, 2]\ntarget = [0, 1, 2]"),
            "same.toml:9: keyframes[1].target: the target is the position: no direction",
        ),
        (
            "nan.toml",
            toml_keys("position = [0, nan, 2]\ntarget = [0, 1, 0]"),
            "nan.toml:8: keyframes[1].position: [0.0, NaN, 2.0]: every coordinate must be finite",
        ),
        (
            "back.toml",
            toml_keys("position = [0, 1, 2]\ntarget = [0, 1, 0]").replace("time = 1", "time = -1"),
            "back.toml:7: keyframes[1].time: -1 is before the previous keyframe's 0",
        ),
        (
            "type.toml",
            toml_keys("position = 0\ntarget = [0, 1, 0]"),
            "type.toml:8: keyframes.position: invalid type: integer `0`",
        ),
        (
            "same.json",
            r#"{"keyframes": [{"time": 0, "position": [1, 2, 3], "target": [1, 2, 3]}]}"#.into(),
            "same.json: keyframes[0].target: the target is the position: no direction",
        ),
    ];
    for (name, text, expected) in cases {
        let file = dir.write(name, &text);
        let e = CameraPath::from_file(&file).unwrap_err().to_string();
        let camera = format!("camera path {}", dir.0.join(expected).display());
        assert!(e.starts_with(&camera), "{name}: {e}\nwanted {camera}");
        let e = LightPath::from_file(&file).unwrap_err().to_string();
        let light = format!("light path {}", dir.0.join(expected).display());
        assert!(e.starts_with(&light), "{name}: {e}\nwanted {light}");
    }
}

/// Issue 62 items 9 and 22: a FIFO or a device where a file is read is refused by name
/// before it is opened (opening a FIFO blocks until a writer comes; /dev/zero never ends):
/// as a model, a material library, a texture, a scene file and a keyframe file. The calls run
/// on a thread so that a regression fails the test instead of hanging it.
#[test]
fn fifos_and_devices_are_refused_before_they_are_opened() {
    let dir = TempDir::new("fifos");
    for name in ["model.obj", "scene.toml", "path.json", "lib.mtl", "tex.png"] {
        let status = std::process::Command::new("mkfifo")
            .arg(dir.0.join(name))
            .status()
            .unwrap();
        assert!(status.success(), "mkfifo {name}");
    }
    let quad = "v 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nf 1/1 2/2 3/3\n";
    dir.write("fifo_mtl.obj", &format!("mtllib lib.mtl\nusemtl m\n{quad}"));
    dir.write(
        "zero_mtl.obj",
        &format!("mtllib /dev/zero\nusemtl m\n{quad}"),
    );
    dir.write("tex.mtl", "newmtl m\nKd 0.5 0.5 0.5\nmap_Kd tex.png\n");
    dir.write("fifo_tex.obj", &format!("mtllib tex.mtl\nusemtl m\n{quad}"));
    let root = dir.0.clone();
    let errors = hang_guard(move || {
        let err = |r: Result<(), SceneError>| r.unwrap_err().to_string();
        let warnings = |name: &str| {
            load_obj(&root.join(name))
                .unwrap()
                .stats
                .warnings
                .join("\n")
        };
        vec![
            err(load_obj(&root.join("model.obj")).map(drop)),
            err(load_scene(root.join("model.obj").to_str().unwrap(), None).map(drop)),
            err(load_scene(root.join("scene.toml").to_str().unwrap(), None).map(drop)),
            err(CameraPath::from_file(&root.join("path.json")).map(drop)),
            err(LightPath::from_file(&root.join("path.json")).map(drop)),
            err(load_scene("/dev/zero", None).map(drop)),
            warnings("fifo_mtl.obj"),
            warnings("zero_mtl.obj"),
            warnings("fifo_tex.obj"),
        ]
    });
    for (i, e) in errors.iter().enumerate() {
        let wanted = match i {
            1 => "model.obj is a FIFO (named pipe), not a model file",
            5 => "/dev/zero is a character device, not a model file",
            7 => "it is a character device, not a regular file",
            _ => "it is a FIFO (named pipe), not a regular file",
        };
        assert!(e.contains(wanted), "case {i}: {e}");
    }
    assert!(errors[0].contains("model.obj"), "{}", errors[0]);
    assert!(errors[6].contains("lib.mtl") && errors[6].contains("default material"));
    assert!(errors[8].contains("tex.png") && errors[8].contains("Kd colour"));
}

/// Run `f` on a thread; a call that never returns fails the test (a hang guard far above
/// any run time, not a timing assertion).
fn hang_guard<T: Send + 'static>(f: impl FnOnce() -> T + Send + 'static) -> T {
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || tx.send(f()).ok());
    rx.recv_timeout(std::time::Duration::from_secs(600))
        .expect("the call hung (blocked on a FIFO or an endless device)")
}

/// Issue 62 item 22: a material library over 16 MiB is refused with the limit named, and the
/// model keeps the default material.
#[test]
fn an_oversized_material_library_is_refused() {
    let dir = TempDir::new("big-mtl");
    let mut mtl = b"newmtl m\nKd 0.5 0.5 0.5\n".to_vec();
    mtl.resize((16 << 20) + 1, b'\n');
    std::fs::write(dir.0.join("big.mtl"), mtl).unwrap();
    let obj = dir.write(
        "big.obj",
        "mtllib big.mtl\nusemtl m\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
    );
    let m = load_obj(&obj).unwrap();
    let w = m.stats.warnings.join("\n");
    assert!(
        w.contains("big.mtl") && w.contains("larger than the limit of 16 MiB"),
        "{w}"
    );
    assert_eq!(m.materials[0].diffuse, [0.8; 3]);
}

/// Issue 62 item 20: a `map_Kd` file name in Latin-1 (not UTF-8) finds its file by its bytes.
#[test]
fn a_latin1_texture_name_is_found() {
    use std::os::unix::ffi::OsStrExt;
    let dir = TempDir::new("latin1");
    let name = std::ffi::OsStr::from_bytes(b"caf\xe9.png");
    image::RgbaImage::from_pixel(1, 1, image::Rgba([0, 255, 0, 255]))
        .save_with_format(dir.0.join(name), image::ImageFormat::Png)
        .unwrap();
    std::fs::write(
        dir.0.join("l.mtl"),
        b"newmtl m\nKd 1 1 1\nmap_Kd caf\xe9.png\n",
    )
    .unwrap();
    let obj = dir.write(
        "l.obj",
        "mtllib l.mtl\nusemtl m\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n",
    );
    let m = load_obj(&obj).unwrap();
    assert!(m.stats.warnings.is_empty(), "{:?}", m.stats.warnings);
    let tex = m.materials[0]
        .diffuse_texture
        .as_ref()
        .expect("the texture");
    assert_eq!(tex.path.file_name(), Some(name));
    assert_eq!(&tex.rgba8[..4], &[0, 255, 0, 255]);
}

/// The built-in rooms' orbit keeps the eye inside the room, above the boxes and the box
/// room's model, at its circle's radius; a loaded model's orbit turns around it at the base
/// camera's distance.
#[test]
fn builtin_paths_from_a_scene() {
    let orbit = CameraPath::parse("orbit").unwrap();
    let s = load_scene("cornell-box", None).unwrap();
    let room = s.mesh.bounds;
    let Orbit::Inside { center, radius, .. } = s.orbit() else {
        panic!("the Cornell box orbits inside: {:?}", s.orbit());
    };
    for f in 0..240 {
        let c = orbit.camera_at(&s.camera, &s.orbit(), f as f32 * 0.05);
        let p = c.position;
        assert!(
            p.cmpgt(room.min).all() && p.cmplt(room.max).all(),
            "frame {f}: {p} outside the room {room:?}"
        );
        let horizontal = Vec3::new(p.x - center.x, 0.0, p.z - center.z).length();
        assert!((horizontal - radius).abs() < 1e-4);
        // Above the short box (0.6 m) and the box room's model (0.9 m); in front of the tall
        // box, whose footprint ends at z = 0.09.
        assert!(p.y > 0.9 && p.z > 0.1, "frame {f}: {p}");
        assert_eq!(c.target, center);
    }
    assert_eq!(CameraPath::parse("static").unwrap().name(), "static");
    assert_eq!(CameraPath::parse("dolly").unwrap().name(), "dolly:6s");
    assert_eq!(CameraPath::parse("orbit:3s").unwrap().name(), "orbit:3s");
}

// ---------------------------------------------------------------- robustness

/// Deterministic mutation fuzzing of the fixtures: every result is either a mesh with finite
/// data and valid indices or an error; never a panic, and never tobj's line-less error (which
/// would mean the validation pass missed something tobj rejects).
#[test]
fn mutated_fixtures_never_panic() {
    const ATOMS: [&str; 30] = [
        "v",
        "vt",
        "vn",
        "f",
        "l",
        "o",
        "g",
        "usemtl",
        "mtllib",
        "#",
        "1",
        "-1",
        "0",
        "-7",
        "2/1",
        "1//1",
        "1/1/1",
        "/",
        "nan",
        "inf",
        "1e40",
        "1e-40",
        "\n",
        "\r\n",
        "x",
        "é",
        "1/2/3/4",
        "99999999999999999999",
        "\u{feff}",
        "bad_kd.mtl",
    ];
    let dir = TempDir::new("fuzz");
    dir.write("bad_kd.mtl", "newmtl half\nKd 0.5\n");
    let seeds: Vec<String> = std::fs::read_dir(fixture(""))
        .unwrap()
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "obj"))
        .map(|p| std::fs::read_to_string(p).unwrap())
        .collect();
    let mut state = 0x1234_5678_9abc_def0u64;
    let mut rand = |n: usize| {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state % n as u64) as usize
    };
    let path = dir.0.join("mutant.obj");
    for _ in 0..2000 {
        let mut text: Vec<char> = seeds[rand(seeds.len())].chars().collect();
        for _ in 0..1 + rand(5) {
            let at = rand(text.len() + 1);
            if rand(3) == 0 && at < text.len() {
                text.remove(at);
            } else {
                let atom = format!(" {}", ATOMS[rand(ATOMS.len())]);
                text.splice(at..at, atom.chars());
            }
        }
        let text: String = text.into_iter().collect();
        std::fs::write(&path, &text).unwrap();
        match std::panic::catch_unwind(|| load_obj(&path)) {
            Ok(Ok(m)) => {
                let finite = m.vertices.iter().all(|v| {
                    v.position
                        .iter()
                        .chain(&v.normal)
                        .chain(&v.uv)
                        .all(|x| x.is_finite())
                });
                assert!(finite, "non-finite vertex data from:\n{text}");
                assert!(m.indices.iter().all(|&i| (i as usize) < m.vertices.len()));
                assert!(m.triangle_count() > 0);
            }
            Ok(Err(SceneError::Obj { message, .. })) => {
                panic!("validation missed '{message}' in:\n{text}")
            }
            Ok(Err(_)) => {}
            Err(_) => panic!("panicked on:\n{text}"),
        }
    }
}
