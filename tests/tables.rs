//! `ssgi table`: both thesis tables end to end on lavapipe at 64x64 with the real scene files
//! (SSGI_ASSETS), under validation + synchronization validation. Checks the report's
//! structure and invariants: every scene and row present, all times positive, reuse computes
//! fewer pixels than no reuse, the reference against itself has error 0, one CSV row per frame,
//! PNG files that decode.

use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Command;

/// Frames measured per row, and warmup frames at the first camera: more than the 36 patterns
/// after which a pixel counts as converged, so reuse has converged pixels to skip.
const FRAMES: u32 = 10;
const WARMUP: u32 = 40;

/// The asset directory, or None (with a message) when SSGI_ASSETS is not set.
fn assets() -> Option<PathBuf> {
    match std::env::var_os("SSGI_ASSETS").filter(|v| !v.is_empty()) {
        Some(dir) => Some(PathBuf::from(dir)),
        None => {
            println!("skipped: SSGI_ASSETS not set");
            None
        }
    }
}

fn out_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("ssgi-tables-{}-{name}", std::process::id()));
    std::fs::remove_dir_all(&dir).ok();
    dir
}

/// Run `ssgi --validation table <table>` and return report.json.
fn run_table(assets: &Path, table: &str, out: &Path) -> Value {
    let output = Command::new(env!("CARGO_BIN_EXE_ssgi"))
        .arg("--validation")
        .arg("--assets")
        .arg(assets)
        .args(["table", table, "--size", "64x64"])
        .args([
            "--frames",
            &FRAMES.to_string(),
            "--warmup",
            &WARMUP.to_string(),
        ])
        .arg("--out")
        .arg(out)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        output.status.success(),
        "ssgi table {table} failed:\n{stderr}"
    );
    assert!(
        !stderr.contains("vulkan: ["),
        "validation messages:\n{stderr}"
    );
    let text = std::fs::read_to_string(out.join("report.json")).unwrap();
    serde_json::from_str(&text).unwrap()
}

fn num(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

fn png_size(path: &Path) -> (u32, u32) {
    let img = image::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    (img.width(), img.height())
}

/// Structure and invariants shared by both tables; returns the scenes.
fn check_report(report: &Value, out: &Path, table: &str, names: &[&str]) -> Vec<Value> {
    assert_eq!(report["version"], 1);
    assert_eq!(report["table"], table);
    assert_eq!(
        (report["width"].as_u64(), report["height"].as_u64()),
        (Some(64), Some(64))
    );
    assert_eq!(report["frames"], FRAMES);
    assert_eq!(report["warmup"], WARMUP);
    assert!(report["device"].as_str().is_some_and(|d| !d.is_empty()));
    assert!(report["driver"].is_string());
    assert!(report["command"].as_str().unwrap().contains(table));
    assert_eq!(report["base_config"]["ao"]["samples"], 32);
    let notes = report["notes"].to_string();
    assert!(notes.contains("pending issue 5"), "{notes}");

    let scenes = report["scenes"].as_array().unwrap().clone();
    let got: Vec<&str> = scenes.iter().map(|s| s["name"].as_str().unwrap()).collect();
    assert_eq!(got, names);
    for s in &scenes {
        let name = s["name"].as_str().unwrap();
        let rows = s["rows"].as_array().unwrap();
        let kinds: Vec<&str> = rows.iter().map(|r| r["kind"].as_str().unwrap()).collect();
        assert_eq!(kinds, ["reuse", "no_reuse", "reference"], "{name}");
        for row in rows {
            let kind = row["kind"].as_str().unwrap();
            let what = format!("{name} {kind}");
            for group in ["ao", "total"] {
                let ms = num(&row["ms"][group]);
                assert!(ms.is_finite() && ms > 0.0, "{what}: {group} {ms} ms");
                assert!(num(&row["fps"][group]) > 0.0, "{what}");
            }
            for pass in row["report"]["passes"].as_array().unwrap() {
                if pass["recorded"].as_u64().unwrap() > 0 {
                    assert!(num(&pass["median_ms"]) > 0.0, "{what}: {pass}");
                }
            }
            if kind != "reference" {
                assert_eq!(row["measured_frames"], FRAMES, "{what}");
            }
            for buffer in ["final", "ao", "direct", "shadow"] {
                let e = &row["error"][buffer];
                assert!(e["pixels"].as_u64().unwrap() > 0, "{what}: {buffer} {e}");
                assert_eq!(e["non_finite"], 0, "{what}: {buffer}");
                let (rmse, max) = (num(&e["rmse"]), num(&e["max_abs"]));
                assert!(rmse >= 0.0 && max >= rmse, "{what}: {buffer} {e}");
                if kind == "reference" {
                    assert_eq!(
                        (rmse, max),
                        (0.0, 0.0),
                        "{what}: {buffer}: reference vs itself"
                    );
                }
            }
        }
        let pixels = |r: &Value| num(&r["ssao_pixels_per_frame"]);
        assert!(
            pixels(&rows[0]) < pixels(&rows[1]),
            "{name}: reuse computes {} pixels per frame, no reuse {}",
            pixels(&rows[0]),
            pixels(&rows[1])
        );
        assert!(num(&s["speedups"]["ao"]) > 0.0, "{name}");
        for f in s["files"].as_array().unwrap() {
            let f = f.as_str().unwrap();
            assert!(out.join(f).is_file(), "{name}: {f} missing");
            if let Some(stem) = f.strip_suffix(".png") {
                if ["-reuse", "-no_reuse", "-reference"]
                    .iter()
                    .any(|k| stem.ends_with(k))
                {
                    assert_eq!(png_size(&out.join(f)), (64, 64), "{f}");
                }
            }
        }
    }
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    for name in names {
        assert!(md.contains(name), "report.md lacks {name}");
    }
    assert!(md.contains(report["device"].as_str().unwrap()));
    let csv = std::fs::read_to_string(out.join(format!("{table}.csv"))).unwrap();
    assert_eq!(csv.lines().count(), 1 + 3 * names.len(), "{csv}");
    scenes
}

#[test]
fn thesis_4_1_end_to_end() {
    let Some(assets) = assets() else { return };
    let out = out_dir("4.1");
    let report = run_table(&assets, "thesis-4.1", &out);
    let scenes = check_report(
        &report,
        &out,
        "thesis-4.1",
        &["Venus", "Dragon", "Bunny", "Buddha"],
    );
    assert_eq!(scenes[0]["spec"], "box:venus");
    assert_eq!(num(&scenes[0]["thesis"]["reuse"]["ssao"]), 206.0);
    assert_eq!(num(&scenes[1]["thesis"]["no_reuse"]["total"]), 38.0);
    assert!((num(&scenes[1]["thesis_speedups"]["ssao"]) - 426.0 / 280.0).abs() < 1e-9);
    // The dragon is decimated to the thesis's 6,514 faces (plus the room's walls), and says so.
    let note = scenes[1]["note"].as_str().unwrap();
    assert!(
        note.contains("not available") && note.contains("decimated"),
        "{note}"
    );
    let dragon = scenes[1]["triangles"].as_u64().unwrap();
    assert!(
        (6_000..=6_514 + 40).contains(&dragon),
        "dragon scene has {dragon} triangles"
    );
    assert!(scenes.iter().all(|s| s["path"] == "paths/box.json"));
    std::fs::remove_dir_all(&out).ok();
}

#[test]
fn thesis_walkthroughs_end_to_end() {
    let Some(assets) = assets() else { return };
    let out = out_dir("walkthroughs");
    let report = run_table(&assets, "thesis-walkthroughs", &out);
    let scenes = check_report(
        &report,
        &out,
        "thesis-walkthroughs",
        &["Sponza", "Sibenik", "Conference"],
    );
    for s in &scenes {
        let asset = s["spec"].as_str().unwrap();
        assert_eq!(s["path"], format!("paths/{asset}.json"));
        assert!(s["thesis"].is_null());
        // One CSV row per measured frame, frames 0.. in order, a value in every timing column.
        let csv = std::fs::read_to_string(out.join(format!("walkthrough-{asset}.csv"))).unwrap();
        let mut lines = csv.lines();
        let header: Vec<&str> = lines.next().unwrap().split(',').collect();
        let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
        assert_eq!(rows.len(), FRAMES as usize, "{asset}");
        for (i, r) in rows.iter().enumerate() {
            assert_eq!(r.len(), header.len(), "{asset} row {i}");
            assert_eq!(r[0], i.to_string());
            for col in [
                "reuse_total_ms",
                "no_reuse_total_ms",
                "reuse_ao_ms",
                "no_reuse_ao_ms",
            ] {
                let c = header.iter().position(|h| *h == col).unwrap();
                let v: f64 = r[c].parse().unwrap();
                assert!(v > 0.0, "{asset} frame {i}: {col} = {v}");
            }
            for col in ["reuse_recomputed_fraction", "no_reuse_recomputed_fraction"] {
                let c = header.iter().position(|h| *h == col).unwrap();
                let v: f64 = r[c].parse().unwrap();
                assert!((0.0..=1.0).contains(&v), "{asset} frame {i}: {col} = {v}");
            }
        }
        for plot in ["time", "recomputed"] {
            let f = format!("walkthrough-{asset}-{plot}.png");
            assert!(s["files"].to_string().contains(&f), "{f} not listed");
            assert_eq!(png_size(&out.join(&f)), (900, 480), "{f}");
        }
    }
    std::fs::remove_dir_all(&out).ok();
}

#[test]
fn missing_scene_files_name_the_file_and_the_fix() {
    let empty = out_dir("empty-assets");
    std::fs::create_dir_all(&empty).unwrap();
    for (table, asset) in [("thesis-4.1", "venus"), ("thesis-walkthroughs", "sponza")] {
        let output = Command::new(env!("CARGO_BIN_EXE_ssgi"))
            .arg("--assets")
            .arg(&empty)
            .args(["table", table, "--size", "16x16", "--frames", "1"])
            .arg("--out")
            .arg(empty.join("out"))
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(!output.status.success(), "{table} succeeded without assets");
        for needle in [
            asset,
            &empty.display().to_string(),
            "--assets",
            "SSGI_ASSETS",
        ] {
            assert!(
                stderr.contains(needle),
                "{table}: error lacks {needle:?}:\n{stderr}"
            );
        }
        assert!(
            !empty.join("out").exists(),
            "{table} wrote output before failing"
        );
    }
    std::fs::remove_dir_all(&empty).ok();
}
