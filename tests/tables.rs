//! `ssgi table`: both thesis tables end to end on lavapipe at 80x80 with the real scene files
//! (SSGI_ASSETS), under validation + synchronization validation. Checks the report's
//! structure and invariants: every scene and row present, all times positive, reuse computes
//! fewer pixels than no reuse, the reference against itself has error 0, one CSV row per frame,
//! PNG files that decode.

#[path = "common/schema.rs"]
mod schema;

use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Command;

/// Frames measured per row, and warmup frames at the first camera: more than the 36 patterns
/// after which a pixel counts as converged, so reuse has converged pixels to skip.
const FRAMES: u32 = 4;
const WARMUP: u32 = 37;
/// 80x80: more than one 64x64 refresh tile (at 64x64 the tile refreshed every frame is the
/// whole image, so reuse could not compute fewer pixels).
const SIZE: &str = "80x80";
/// Indirect light costs ~0.2 s per frame at 80x80 on lavapipe; the invariant runs leave it
/// out and `indirect_columns` covers it at 32x32.
const NO_INDIRECT: &str = "direct,ao";

/// The asset directory; a test that needs it fails (never skips) when SSGI_ASSETS is not set.
fn assets() -> PathBuf {
    match std::env::var_os("SSGI_ASSETS").filter(|v| !v.is_empty()) {
        Some(dir) => PathBuf::from(dir),
        None => panic!("SSGI_ASSETS is not set: this test needs the papers' models (the shared scenes directory, ../shared/scenes in this workspace); tools/test sets it"),
    }
}

fn out_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("ssgi-tables-{}-{name}", std::process::id()));
    std::fs::remove_dir_all(&dir).ok();
    dir
}

/// How a table is run.
struct Run<'a> {
    table: &'a str,
    size: &'a str,
    frames: u32,
    warmup: u32,
    effects: &'a str,
}

impl Run<'_> {
    fn invariants(table: &str) -> Run<'_> {
        Run {
            table,
            size: SIZE,
            frames: FRAMES,
            warmup: WARMUP,
            effects: NO_INDIRECT,
        }
    }
}

/// Run `ssgi --validation table ...` and return report.json.
fn run_table(assets: &Path, run: &Run<'_>, out: &Path) -> Value {
    let output = Command::new(env!("CARGO_BIN_EXE_ssgi"))
        .arg("--validation")
        .arg("--assets")
        .arg(assets)
        .args([
            "table",
            run.table,
            "--size",
            run.size,
            "--effects",
            run.effects,
        ])
        .args(["--frames", &run.frames.to_string()])
        .args(["--warmup", &run.warmup.to_string()])
        .arg("--out")
        .arg(out)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    let table = run.table;
    assert!(
        output.status.success(),
        "ssgi table {table} failed:\n{stderr}"
    );
    assert!(
        !stderr.contains("vulkan: ["),
        "validation messages:\n{stderr}"
    );
    let text = std::fs::read_to_string(out.join("report.json")).unwrap();
    let report = serde_json::from_str(&text).unwrap();
    schema::assert_follows("thesis-table", &report);
    report
}

fn num(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

fn png_size(path: &Path) -> (u32, u32) {
    let img = image::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    (img.width(), img.height())
}

/// Structure and invariants of every report; returns the scenes.
fn check_report(report: &Value, out: &Path, run: &Run<'_>, names: &[&str]) -> Vec<Value> {
    let table = run.table;
    let indirect = run.effects == "all";
    let side: u64 = run.size.split('x').next().unwrap().parse().unwrap();
    assert_eq!(report["version"], 1);
    assert_eq!(report["table"], table);
    assert_eq!(
        (report["width"].as_u64(), report["height"].as_u64()),
        (Some(side), Some(side))
    );
    assert_eq!(report["frames"], run.frames);
    assert_eq!(report["warmup"], run.warmup);
    assert_eq!(report["base_config"]["effects"]["indirect"], indirect);
    assert!(report["device"].as_str().is_some_and(|d| !d.is_empty()));
    assert!(report["driver"].is_string());
    assert!(report["command"].as_str().unwrap().contains(table));
    assert_eq!(report["base_config"]["ao"]["samples"], 32);
    let notes = report["notes"].to_string();
    assert!(notes.contains("Reproject"), "{notes}");

    let scenes = report["scenes"].as_array().unwrap().clone();
    let got: Vec<&str> = scenes.iter().map(|s| s["name"].as_str().unwrap()).collect();
    assert_eq!(got, names);
    for s in &scenes {
        let name = s["name"].as_str().unwrap();
        let rows = s["rows"].as_array().unwrap();
        let kinds: Vec<&str> = rows.iter().map(|r| r["kind"].as_str().unwrap()).collect();
        assert_eq!(kinds, ["reuse", "no_reuse", "reference"], "{name}");
        // The ground truth's quality is reported for every compared buffer.
        let quality = &s["ground_truth"];
        for b in ["ao", "direct", "shadow"] {
            assert!(
                quality[b]["samples_per_pixel"].as_u64().is_some(),
                "{name} {b}: {quality}"
            );
        }
        for row in rows {
            let kind = row["kind"].as_str().unwrap();
            let what = format!("{name} {kind}");
            // Every row is scored against the CPU ground truth, the final image with FLIP.
            for b in ["final", "ao", "direct", "shadow"] {
                let rmse = row["truth"][b]["rmse"].as_f64();
                assert!(
                    rmse.is_some_and(|e| e.is_finite() && e >= 0.0),
                    "{what} {b}"
                );
            }
            let flip = row["truth"]["final"]["flip"].as_f64();
            assert!(flip.is_some_and(|f| (0.0..=1.0).contains(&f)), "{what}");
            let groups: &[&str] = if indirect {
                &["ao", "indirect", "total"]
            } else {
                &["ao", "total"]
            };
            if !indirect {
                assert!(row["ms"]["indirect"].is_null(), "{what}: indirect ran");
            }
            for &group in groups {
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
                assert_eq!(row["measured_frames"], run.frames, "{what}");
            }
            let buffers: &[&str] = if indirect {
                &["final", "ao", "indirect", "direct", "shadow"]
            } else {
                &["final", "ao", "direct", "shadow"]
            };
            assert_eq!(
                row["error"].as_object().unwrap().len(),
                buffers.len(),
                "{what}"
            );
            for &buffer in buffers {
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
        if run.warmup > 36 {
            assert!(
                pixels(&rows[0]) < pixels(&rows[1]),
                "{name}: reuse computes {} pixels per frame, no reuse {}",
                pixels(&rows[0]),
                pixels(&rows[1])
            );
        }
        assert!(pixels(&rows[0]) <= pixels(&rows[1]), "{name}");
        let speedup = num(&rows[1]["ms"]["ao"]) / num(&rows[0]["ms"]["ao"]);
        assert!((num(&s["speedups"]["ao"]) - speedup).abs() < 1e-9, "{name}");
        for f in s["files"].as_array().unwrap() {
            let f = f.as_str().unwrap();
            assert!(out.join(f).is_file(), "{name}: {f} missing");
            if let Some(stem) = f.strip_suffix(".png") {
                if ["-reuse", "-no_reuse", "-reference"]
                    .iter()
                    .any(|k| stem.ends_with(k))
                {
                    assert_eq!(png_size(&out.join(f)), (side as u32, side as u32), "{f}");
                }
            }
        }
    }
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    for name in names {
        assert!(md.contains(name), "report.md lacks {name}");
    }
    assert!(md.contains(report["device"].as_str().unwrap()));
    assert!(md.contains("## Error against the ground truth"), "{md}");
    let csv = std::fs::read_to_string(out.join(format!("{table}.csv"))).unwrap();
    let csv_header = csv.lines().next().unwrap();
    assert!(csv_header.contains("final_truth_flip"));
    // Columns of effects the run left out are dropped, not printed empty.
    assert_eq!(csv_header.contains("indirect"), indirect, "{csv_header}");
    assert_eq!(md.contains("ours Indirect"), indirect);
    assert_eq!(
        md.contains("thesis indirect fps"),
        indirect && table == "thesis-4.1"
    );
    assert_eq!(csv.lines().count(), 1 + 3 * names.len(), "{csv}");
    scenes
}

#[test]
fn thesis_4_1_end_to_end() {
    let assets = assets();
    let out = out_dir("4.1");
    let run = Run::invariants("thesis-4.1");
    let report = run_table(&assets, &run, &out);
    let scenes = check_report(&report, &out, &run, &["Venus", "Dragon", "Bunny", "Buddha"]);
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
    let assets = assets();
    let out = out_dir("walkthroughs");
    let run = Run::invariants("thesis-walkthroughs");
    let report = run_table(&assets, &run, &out);
    let scenes = check_report(&report, &out, &run, &["Sponza", "Sibenik", "Conference"]);
    for s in &scenes {
        let asset = s["spec"].as_str().unwrap();
        assert_eq!(s["path"], format!("paths/{asset}.json"));
        assert!(s["thesis"].is_null());
        // One CSV row per measured frame, frames 0.. in order, a value in every timing column.
        let csv = std::fs::read_to_string(out.join(format!("walkthrough-{asset}.csv"))).unwrap();
        let mut lines = csv.lines();
        let header: Vec<&str> = lines.next().unwrap().split(',').collect();
        let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
        assert_eq!(rows.len(), run.frames as usize, "{asset}");
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

/// `ssgi table dynamic`: the ball with the swinging light, and with the light still, get the
/// walkthroughs' rows and checks; something the light sees moves on every measured frame
/// after the first (the warmup holds time 0), so the reuse rows record the light view on each
/// of those, and the series files are there.
#[test]
fn dynamic_end_to_end() {
    let assets = assets();
    let out = out_dir("dynamic");
    let run = Run::invariants("dynamic");
    let report = run_table(&assets, &run, &out);
    let scenes = check_report(
        &report,
        &out,
        &run,
        &["Ball & swinging light", "Ball, light still"],
    );
    // The swinging light moves on every measured frame but the first; the ball, in the
    // light's sight, moves the light view on each of them too.
    for s in &scenes {
        let reuse = &s["rows"][0];
        let passes = reuse["report"]["passes"].as_array().unwrap();
        let light_view = passes.iter().find(|p| p["name"] == "light_view").unwrap();
        assert_eq!(light_view["recorded"], run.frames - 1, "{light_view}");
        let stem = s["spec"].as_str().unwrap();
        for f in ["csv", "time.png", "recomputed.png"] {
            let sep = if f == "csv" { "." } else { "-" };
            let file = format!("dynamic-{stem}{sep}{f}");
            assert!(out.join(&file).is_file(), "{file}");
        }
    }
    std::fs::remove_dir_all(&out).ok();
}

/// Every effect, as the thesis ran it, at a size where lavapipe's indirect light is cheap:
/// the indirect columns and buffers are there, the reference against itself is 0.
#[test]
fn indirect_columns() {
    let assets = assets();
    let out = out_dir("indirect");
    let run = Run {
        table: "thesis-4.1",
        size: "32x32",
        frames: 2,
        warmup: 1,
        effects: "all",
    };
    let report = run_table(&assets, &run, &out);
    let scenes = check_report(&report, &out, &run, &["Venus", "Dragon", "Bunny", "Buddha"]);
    for s in &scenes {
        assert!(num(&s["speedups"]["indirect"]) > 0.0, "{}", s["name"]);
        let reference = &s["rows"][2];
        assert_eq!(reference["config"]["indirect"]["vpls"], 16384);
        assert_eq!(reference["config"]["ao"]["patterns"], 32);
    }
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(
        md.contains("Indirect ms") && md.contains("thesis Indirect"),
        "{md}"
    );
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

/// `ssgi --validation table ARGS --out OUT` for a table with its own report format: it
/// succeeds without validation messages and writes report.json in docs/formats.md's `schema`.
fn own_format_table(args: &[&str], out: &Path, schema: &str) -> Value {
    let output = Command::new(env!("CARGO_BIN_EXE_ssgi"))
        .arg("--validation")
        .arg("--assets")
        .arg(assets())
        .arg("table")
        .args(args)
        .arg("--out")
        .arg(out)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "ssgi table failed:\n{stderr}");
    assert!(
        !stderr.contains("vulkan: ["),
        "validation messages:\n{stderr}"
    );
    let text = std::fs::read_to_string(out.join("report.json")).unwrap();
    let report: Value = serde_json::from_str(&text).unwrap();
    schema::assert_follows(schema, &report);
    report
}

/// `ssgi table szentandrasi-1` at 64x48: the paper's three scenes and seven rows in order, its
/// numbers beside ours, every time and error finite, the sample counters matching each row's
/// setting (the adaptive row between 20 and 50), the passes each row needs (two steps: the
/// bounce pass; subsampling: the upsampling), one PNG per row and one CSV line per row.
#[test]
fn szentandrasi_1_end_to_end() {
    let out = out_dir("szentandrasi-1");
    let report = own_format_table(
        &[
            "szentandrasi-1",
            "--size",
            "64x48",
            "--frames",
            "2",
            "--warmup",
            "1",
        ],
        &out,
        "szentandrasi-table",
    );
    assert_eq!(report["version"], 1);
    assert_eq!(report["table"], "szentandrasi-1");
    assert_eq!(
        (report["width"].as_u64(), report["height"].as_u64()),
        (Some(64), Some(48))
    );
    assert_eq!(report["reference_samples"], 1024);
    let scenes = report["scenes"].as_array().unwrap();
    let names: Vec<&str> = scenes.iter().map(|s| s["name"].as_str().unwrap()).collect();
    assert_eq!(names, ["Pyramids", "Cornell box", "Dragon"]);
    assert!(scenes[2]["note"]
        .as_str()
        .unwrap()
        .contains("not available"));
    let labels = [
        "SSAO no subsampling",
        "SSDO 2 steps",
        "SSDO no subsampling",
        "SSAO",
        "SSDO",
        "SSDO",
        "SSDO with preprocessing",
    ];
    for (si, s) in scenes.iter().enumerate() {
        let name = names[si];
        let rows = s["rows"].as_array().unwrap();
        let got: Vec<&str> = rows.iter().map(|r| r["label"].as_str().unwrap()).collect();
        assert_eq!(got, labels, "{name}");
        for r in rows {
            let label = r["label"].as_str().unwrap();
            let (total, ssdo) = (num(&r["total_ms"]), num(&r["ssdo_ms"]));
            assert!(
                total > 0.0 && ssdo > 0.0 && ssdo < total,
                "{name} {label}: {r}"
            );
            assert!((num(&r["fps"]) - 1000.0 / total).abs() < 1e-6);
            let rmse = num(&r["final_rmse"]);
            assert!((0.0..0.2).contains(&rmse), "{name} {label}: RMSE {rmse}");
            let spp = num(&r["samples_per_pixel"]);
            if r["adaptive"] == true {
                assert!((20.0..=50.0).contains(&spp), "{name} {label}: {spp}");
            } else {
                assert_eq!(spp, num(&r["samples"]), "{name} {label}");
            }
            let passes: Vec<&str> = r["report"]["passes"]
                .as_array()
                .unwrap()
                .iter()
                .map(|p| p["name"].as_str().unwrap())
                .collect();
            assert_eq!(
                passes.contains(&"ssdo_upsample"),
                r["subsampling"] == true,
                "{name} {label}: {passes:?}"
            );
            assert_eq!(passes.contains(&"ssdo_bounce"), r["form"] == "two-step");
            assert!(passes.contains(&"ssdo_bilateral"), "{name} {label}");
            assert_eq!(png_size(&out.join(r["image"].as_str().unwrap())), (64, 48));
        }
        assert_eq!(num(&rows[0]["time_over_first"]), 1.0);
        let ratios = s["ratios"].as_array().unwrap();
        assert_eq!(ratios.len(), 5);
        let paper = [115.0 / 90.5, 127.0 / 83.0, 113.0 / 74.0][si];
        assert!((num(&ratios[0]["paper"]) - paper).abs() < 1e-9, "{name}");
        let ours = num(&ratios[0]["ours_total"]);
        assert!(
            (num(&rows[4]["total_ms"]) / num(&rows[3]["total_ms"]) - ours).abs() < 1e-9,
            "{name}"
        );
    }
    assert_eq!(num(&scenes[1]["rows"][0]["paper_fps"]), 77.0);
    let csv = std::fs::read_to_string(out.join("szentandrasi-1.csv")).unwrap();
    assert_eq!(csv.lines().count(), 1 + 3 * 7);
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(md.contains("SSDO with preprocessing") && md.contains("Paper fps"));
    std::fs::remove_dir_all(&out).ok();
}

/// `ssgi table ao` at 32x32 under validation: every scene with every estimator, with and
/// without the cache, in order; every time, error and flicker finite and positive (the
/// reprojection's time only with the cache); the ground truth's quality per scene.
#[test]
fn ao_end_to_end() {
    let out = out_dir("ao");
    let report = own_format_table(
        &["ao", "--size", "32x32", "--frames", "3", "--warmup", "2"],
        &out,
        "ao-table",
    );
    let scenes = report["scenes"].as_array().unwrap();
    assert_eq!(
        scenes.len(),
        8,
        "Cornell box, 4 Table 4.1 scenes, 3 walkthroughs"
    );
    for s in scenes {
        assert!(num(&s["truth"]["standard_error"]) >= 0.0, "{s}");
        // The visible occluders alone miss some occlusion on every scene (each has corners
        // or objects on a floor that the camera sees only one side of).
        let visible = num(&s["visible_occluders_rmse"]);
        assert!(visible.is_finite() && visible > 0.0, "{s}");
    }
    let rows = report["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 8 * 4 * 2);
    let estimators = ["thesis", "crytek", "szentandrasi", "gtao"];
    for (i, r) in rows.iter().enumerate() {
        assert_eq!(r["scene"], scenes[i / 8]["scene"], "{r}");
        assert_eq!(r["estimator"], estimators[i % 8 / 2], "{r}");
        let cache = i % 2 == 0;
        assert_eq!(r["cache"].as_bool().unwrap(), cache, "{r}");
        for key in ["ao_ms", "frame_ms", "ao_rmse", "flicker"] {
            let v = num(&r[key]);
            assert!(v.is_finite() && v >= 0.0, "{key}: {r}");
        }
        assert!(num(&r["ao_ms"]) > 0.0 && num(&r["ao_rmse"]) > 0.0, "{r}");
        assert_eq!(r["reproject_ms"].is_null(), !cache, "{r}");
    }
    assert!(out.join("ao.csv").is_file());
    std::fs::remove_dir_all(&out).ok();
}

/// `ssgi table chang-flicker` at 32x32 under validation: every filter at every VPL count,
/// still and moving, with per-frame flicker measures, errors and the indirect light's time;
/// more VPLs give the joint bilateral filter less flicker.
#[test]
fn chang_flicker_end_to_end() {
    let out = out_dir("chang-flicker");
    let report = own_format_table(
        &[
            "chang-flicker",
            "--size",
            "32x32",
            "--frames",
            "3",
            "--warmup",
            "2",
            "--set",
            "svgf.iterations=4",
        ],
        &out,
        "chang-flicker-table",
    );
    let notes = report["notes"].to_string();
    assert!(notes.contains("(--set): svgf.iterations=4."), "{notes}");
    let rows = report["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 2 * 5 * 5);
    for r in rows {
        assert_eq!(
            r["flicker"]["final_msd"].as_array().unwrap().len(),
            2,
            "{r}"
        );
        assert_eq!(
            r["flicker"]["indirect_msd"].as_array().unwrap().len(),
            2,
            "{r}"
        );
        assert!(num(&r["final_msd"]) > 0.0, "{r}");
        assert!(num(&r["indirect_relative_rmse"]).is_finite(), "{r}");
        assert!(num(&r["indirect_ms"]) > 0.0, "{r}");
        assert_eq!(
            r["below_threshold"].as_bool().unwrap(),
            num(&r["final_msd"]) < 2.5e-5
        );
    }
    let jbf = |vpls: f64| {
        rows.iter()
            .find(|r| r["motion"] == "static" && r["filter"] == "jbf11" && num(&r["vpls"]) == vpls)
            .map(|r| num(&r["indirect_msd"]))
            .unwrap()
    };
    assert!(jbf(64.0) < jbf(1.0), "{} {}", jbf(64.0), jbf(1.0));
    assert!(out.join("chang-flicker.csv").is_file());
    for plot in [
        "flicker-static",
        "error-static",
        "flicker-moving",
        "error-moving",
    ] {
        assert_eq!(png_size(&out.join(format!("{plot}.png"))), (800, 500));
    }
}

/// `ssgi table chang-1` at 48x48 under validation: three rows (3, 5, 7 bases), every CCIPCA
/// pass timed (the orbit warps every frame), no article numbers at a size it has no row for.
#[test]
fn chang_1_end_to_end() {
    let out = out_dir("chang-1");
    let report = own_format_table(
        &[
            "chang-1", "--size", "48x48", "--frames", "2", "--warmup", "1",
        ],
        &out,
        "chang-1-table",
    );
    assert_eq!(report["effects"], "indirect");
    assert_eq!(num(&report["vpls"]), 3.0);
    let rows = report["rows"].as_array().unwrap();
    let bases: Vec<f64> = rows.iter().map(|r| num(&r["bases"])).collect();
    assert_eq!(bases, [3.0, 5.0, 7.0]);
    for r in rows {
        for key in ["reproject_ms", "ipca_ms", "reconstruct_ms", "input_ms"] {
            assert!(num(&r[key]) > 0.0, "{key}: {r}");
        }
        let sum = num(&r["reproject_ms"]) + num(&r["ipca_ms"]) + num(&r["reconstruct_ms"]);
        assert!((num(&r["total_ms"]) - sum).abs() < 1e-9);
        assert!(r["paper"].is_null());
    }
    assert!(out.join("chang-1.csv").is_file());
}

/// `ssgi table sraa` at 48x48 (one size): the four rows in order, supersampling first and
/// against itself exact, every time finite, the geometry pass only in the SRAA rows, the
/// report's numbers absent at a size it did not measure, SRAA closer to the reference than no
/// antialiasing over the edge pixels, one PNG of the output size per row.
#[test]
fn sraa_end_to_end() {
    let out = out_dir("sraa");
    let report = own_format_table(
        &["sraa", "--size", "48x48", "--frames", "1"],
        &out,
        "sraa-table",
    );
    assert_eq!(report["effects"], "direct");
    let sizes = report["sizes"].as_array().unwrap();
    assert_eq!(sizes.len(), 1);
    let s = &sizes[0];
    assert_eq!((num(&s["width"]), num(&s["height"])), (48.0, 48.0));
    assert!(num(&s["edge_pixels"]) > 0.0, "{s}");
    let rows = s["rows"].as_array().unwrap();
    let modes: Vec<&str> = rows.iter().map(|r| r["mode"].as_str().unwrap()).collect();
    assert_eq!(modes, ["ssaa16", "none", "sraa", "sraa-shadow"]);
    for r in rows {
        let mode = r["mode"].as_str().unwrap();
        assert!(num(&r["total_ms"]) > 0.0, "{mode}: {r}");
        assert_eq!(
            r["geometry_ms"].is_number(),
            mode.starts_with("sraa"),
            "{mode}"
        );
        assert_eq!(r["aa_ms"].is_number(), mode != "none", "{mode}");
        assert!(
            r["paper_total_ms"].is_null(),
            "48x48 is not the report's size"
        );
        let image = out.join(r["image"].as_str().unwrap());
        assert_eq!(png_size(&image), (48, 48), "{mode}");
    }
    assert_eq!(num(&rows[0]["rmse_all"]), 0.0);
    assert_eq!(num(&rows[0]["speedup_over_ssaa"]), 1.0);
    let edges = |i: usize| num(&rows[i]["rmse_edges"]);
    assert!(
        edges(1) > 0.0 && edges(2) < edges(1),
        "{} {}",
        edges(2),
        edges(1)
    );
    let csv = std::fs::read_to_string(out.join("sraa.csv")).unwrap();
    assert_eq!(csv.lines().count(), 1 + 4);
    std::fs::remove_dir_all(&out).ok();
}
