//! The scene files that come with the project (`scenes/*.toml`): each loads, and what
//! `--save-scene` writes of it loads as the same scene, bit for bit. CPU only.

use ssgi::scene::{asset_dir_from_env, load_scene_file};
use std::path::PathBuf;

fn scene_files() -> Vec<PathBuf> {
    let dir = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/scenes"));
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    files.sort();
    files
}

#[test]
fn every_shared_model_has_a_scene_file() {
    let names: Vec<String> = scene_files()
        .iter()
        .map(|p| p.file_stem().unwrap().to_string_lossy().into_owned())
        .collect();
    for model in [
        "bunny",
        "dragon",
        "buddha",
        "venus",
        "sponza",
        "sibenik",
        "conference",
        "cornell-box",
    ] {
        assert!(names.iter().any(|n| n == model), "no scenes/{model}.toml");
    }
}

#[test]
fn scene_files_load_and_round_trip() {
    let assets = asset_dir_from_env().unwrap_or_else(|| {
        panic!("SSGI_ASSETS is not set: this test needs the shared scenes (tools/test sets it)")
    });
    let out = std::env::temp_dir().join(format!("ssgi-scene-files-{}", std::process::id()));
    std::fs::create_dir_all(&out).unwrap();
    for file in scene_files() {
        let first = load_scene_file(&file, Some(&assets))
            .unwrap_or_else(|e| panic!("{}: {e}", file.display()));
        assert!(first.scene.mesh.triangle_count() > 0, "{}", file.display());
        let saved = out.join(file.file_name().unwrap());
        std::fs::write(&saved, first.describe().to_toml()).unwrap();
        let second = load_scene_file(&saved, Some(&assets)).unwrap();
        assert!(
            second.scene == first.scene,
            "{}: the saved scene loads differently",
            file.display()
        );
        assert_eq!(second.camera_path, first.camera_path, "{}", file.display());
    }
}
