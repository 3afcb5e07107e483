//! The `ssgi` binary: the bench JSON report of a 16-frame run, and clear errors for bad input.

#[path = "common/schema.rs"]
mod schema;

use std::process::Command;

fn ssgi() -> Command {
    Command::new(env!("CARGO_BIN_EXE_ssgi"))
}

fn tmp(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("ssgi-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// `--warmup converged` renders until the computed-pixel counters settle: on a static view,
/// until nothing is computed any more. The report says how many frames that took, marks them,
/// and the measured frames compute nothing.
#[test]
fn converged_warmup_measures_the_steady_state() {
    let json = tmp("bench-converged.json");
    let out = ssgi()
        .args(["--validation", "bench", "--scene", "cornell-box"])
        .args(["--size", "64x64", "--rsm-size", "128", "--pcf", "9"])
        .args(["--frames", "4", "--warmup", "converged", "--json"])
        .arg(&json)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "bench failed:\n{stderr}");
    assert!(stderr.contains("warmup: converged after"), "{stderr}");
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    schema::assert_follows("bench", &report);
    // The format check itself: a documented array or object may not be null unless the format
    // says `| null` (it accepted null everywhere once).
    for key in ["frames", "config"] {
        let mut nulled = report.clone();
        nulled[key] = serde_json::Value::Null;
        let errors = schema::check("bench", &nulled);
        assert!(
            errors.iter().any(|e| e.contains(key)),
            "null {key} passed: {errors:?}"
        );
    }
    let warmup = &report["config"]["warmup"];
    assert_eq!(warmup["mode"], "converged");
    assert_eq!(warmup["settled"], true);
    let n = warmup["frames"].as_u64().unwrap();
    // Two windows of the rotation limit (36) at least; a static view settles soon after.
    assert!((72..=200).contains(&n), "warmup of {n} frames");
    let frames = report["frames"].as_array().unwrap();
    assert_eq!(frames.len() as u64, n + 4);
    for f in frames {
        let index = f["index"].as_u64().unwrap();
        assert_eq!(f["warmup"], index < n, "frame {index}");
        if index >= n {
            // Converged and unchanged: skipped entirely (`--skip-unchanged`, on by default),
            // with every pass listed as skipped; a frame that ran computed nothing.
            let passes = f["passes"].as_object().unwrap();
            if passes.is_empty() {
                assert_eq!(f["skip_reasons"]["ssao"], "converged", "frame {index}");
                assert_eq!(f["skip_reasons"]["gbuffer"], "unchanged", "frame {index}");
                continue;
            }
            for effect in ["ssao", "shadow", "indirect"] {
                let key = format!("{effect}_computed_pixels");
                assert_eq!(f["counters"][&key], 0, "frame {index}: {key}");
            }
        }
    }
    assert_eq!(report["skipped_frames"], 4, "a converged static view skips");
}

#[test]
fn bench_json_has_every_pass_and_skips_the_static_light_view() {
    let json = tmp("bench.json");
    let png = tmp("bench.png");
    let out = ssgi()
        .args([
            "--validation",
            "bench",
            "--scene",
            "cornell-box",
            "--size",
            "64x64",
        ])
        .args([
            "--frames",
            "16",
            "--warmup",
            "0",
            "--rsm-size",
            "128",
            "--json",
        ])
        .arg(&json)
        .arg("--out")
        .arg(&png)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "bench failed:\n{stderr}");
    assert!(
        !stderr.contains("vulkan: ["),
        "validation messages:\n{stderr}"
    );
    for pass in ["light_view", "gbuffer", "direct", "composite", "total"] {
        assert!(stdout.contains(pass), "table lacks {pass}:\n{stdout}");
    }
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    schema::assert_follows("bench", &report);
    assert_eq!(report["version"], 1);
    assert_eq!(report["width"], 64);
    assert_eq!(report["height"], 64);
    assert!(report["device"].as_str().is_some_and(|d| !d.is_empty()));
    assert!(report["driver"].is_string());
    assert_eq!(report["config"]["frames"], 16);
    assert_eq!(report["config"]["fps"], 60.0);
    let frames = report["frames"].as_array().unwrap();
    assert_eq!(frames.len(), 16);
    for (i, f) in frames.iter().enumerate() {
        assert_eq!(f["index"], i as u64);
        assert_eq!(f["warmup"], false, "--warmup 0");
        let computed = f["counters"]["ssao_computed_pixels"].as_u64().unwrap();
        let disoccluded = f["counters"]["disoccluded_pixels"].as_u64().unwrap();
        assert!(computed <= 64 * 64, "frame {i}: {computed} SSAO pixels");
        if i == 0 {
            // First frame: no history, every geometry pixel is new and computed.
            assert_eq!(computed, disoccluded, "frame 0");
            assert!(computed > 64 * 64 / 2, "frame 0 covers the box: {computed}");
        } else {
            assert_eq!(disoccluded, 0, "static camera, frame {i}");
        }
    }
    let passes = report["passes"].as_array().unwrap();
    let names: Vec<&str> = passes.iter().map(|p| p["name"].as_str().unwrap()).collect();
    assert_eq!(
        names,
        [
            "light_view",
            "gbuffer",
            "reproject",
            "shadow",
            "direct",
            "ssao",
            "indirect_classify",
            "indirect_gather",
            "indirect_upsample",
            "indirect_fixup",
            "composite"
        ]
    );
    for p in passes {
        let name = p["name"].as_str().unwrap();
        for key in ["median_ms", "mean_ms", "p95_ms"] {
            let v = p[key]
                .as_f64()
                .unwrap_or_else(|| panic!("{name}.{key} missing"));
            assert!(v > 0.0, "{name}.{key} = {v}");
        }
        let (recorded, skipped) = (
            p["recorded"].as_u64().unwrap(),
            p["skipped"].as_u64().unwrap(),
        );
        let expected = match name {
            // Static light: the RSM is rendered once.
            "light_view" => (1, 15),
            // Static camera and light (`--skip-unchanged`): once both halves of the
            // ping-ponged G-buffer hold the view, the G-buffer and the direct light (no
            // history with the default 49-tap grid) are not recorded again.
            "gbuffer" | "shadow" | "direct" => (2, 14),
            // AO and indirect light still accumulate (36 patterns).
            _ => (16, 0),
        };
        assert_eq!((recorded, skipped), expected, "{name}");
        // Every frame that recorded the pass has its time in the per-frame rows.
        let in_frames = frames
            .iter()
            .filter(|f| f["passes"][name].as_f64().is_some_and(|t| t > 0.0))
            .count();
        assert_eq!(in_frames as u64, recorded, "{name}");
    }
    assert!(report["total"]["median_ms"].as_f64().unwrap() > 0.0);
    let png = std::fs::read(&png).unwrap();
    assert_eq!(&png[1..4], b"PNG");
}

fn fails_with(args: &[&str], needle: &str) {
    let out = ssgi().args(args).output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "{args:?} should fail");
    assert!(
        stderr.contains(needle),
        "{args:?}: expected {needle:?} in:\n{stderr}"
    );
    assert!(!stderr.contains("panicked"), "{args:?} panicked:\n{stderr}");
}

#[test]
fn bad_flags_get_clear_errors() {
    fails_with(&["render", "--size", "0x64"], "outside 1..=");
    fails_with(&["render", "--size", "banana"], "WIDTHxHEIGHT");
    fails_with(&["render", "--pcf", "50"], "square");
    fails_with(&["render", "--pcf", "soft"], "--pcf");
    fails_with(&["render", "--ao-attenuation", "-1:0"], "A:B, each finite");
    fails_with(
        &["reference", "--ao-attenuation", "0,1"],
        "--ao-attenuation takes A:B",
    );
    fails_with(&["render", "--ao-steps", "0"], "GTAO steps");
    fails_with(&["bench", "--frames", "0"], "at least 1");
    fails_with(&["render", "--frames", "0"], "at least 1");
    fails_with(&["view", "--frames", "0"], "at least 1");
    fails_with(&["render", "--rsm-size", "0"], "shadow map size");
    fails_with(&["render", "--path", "/nonexistent/path.json"], "path.json");
    fails_with(
        &["render", "--vpls", "all", "--rsm-size", "512"],
        "--rsm-size 128",
    );
    fails_with(&["render", "--vpls", "0"], "--vpls");
    fails_with(&["render", "--effects", "ssdp"], "unknown effect");
    fails_with(&["render", "--effects", "ao,ssdo"], "both darken");
    fails_with(&["render", "--bilateral", "4"], "odd side");
    fails_with(
        &["table", "szentandrasi-1", "--effects", "all"],
        "leave out --effects",
    );
    fails_with(
        &["render", "--effects", "direct,ssdo", "--ssdo", "two-step"],
        "two steps need --reuse off",
    );
    fails_with(
        &["render", "--effects", "direct,ssdo", "--ssdo-scale", "0.5"],
        "--ssdo-scale 0.5 needs --reuse off",
    );
    fails_with(&["render", "--ssdo-scale", "0.25"], "--ssdo-scale takes 1");
    fails_with(&["render", "--ssdo-scale", "nan"], "--ssdo-scale takes 1");
    fails_with(
        &["render", "--ssdo-samples", "adaptive:15-50"],
        "multiples of 10",
    );
    fails_with(&["render", "--ao-position-mips", "4"], "--ao-position-mips");
    fails_with(&["render", "--epsilon", "abs:-1"], "--epsilon");
    fails_with(&["render", "--ema-alpha", "2"], "--ema-alpha");
    fails_with(&["render", "--bias", "nan"], "--bias");
    fails_with(&["render", "--rotation-limit", "4096"], "1..=2048");
    fails_with(&["render", "--mean-cap", "100000"], "1..=2048");
}

#[test]
fn unknown_scene_explains_where_it_looked() {
    let out = ssgi()
        .args([
            "render",
            "--scene",
            "no-such-scene",
            "--assets",
            "/nonexistent-assets",
        ])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(stderr.contains("no-such-scene"), "{stderr}");
    assert!(stderr.contains("cornell-box"), "lists built-ins: {stderr}");
    assert!(
        stderr.contains("SSGI_ASSETS"),
        "says how to set the asset dir: {stderr}"
    );
}

#[test]
fn malformed_obj_is_reported_with_file_and_line() {
    let fixture = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/nan_vertex.obj");
    let out = ssgi()
        .args(["render", "--scene", fixture])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(stderr.contains("nan_vertex.obj:"), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
}

/// `render --dump-gbuffer` writes the buffers that exist in the run and leaves out those of
/// effects that are off (they used to abort the dump).
#[test]
fn dump_leaves_out_the_buffers_of_disabled_effects() {
    let dir = tmp("dump-direct-only");
    let out = ssgi()
        .args([
            "--validation",
            "render",
            "--size",
            "32x32",
            "--rsm-size",
            "128",
            "--effects",
            "direct",
            "--out",
        ])
        .arg(tmp("dump-direct-only.png"))
        .arg("--dump-gbuffer")
        .arg(&dir)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "render failed:\n{stderr}");
    for present in ["shadow", "direct", "gbuffer_normal", "rsm_flux", "output"] {
        assert!(
            dir.join(format!("{present}.png")).is_file(),
            "{present}.png missing"
        );
    }
    for absent in ["ao", "indirect", "discard_mask"] {
        assert!(
            !dir.join(format!("{absent}.png")).exists(),
            "{absent}.png written"
        );
    }
}

/// `--frames 0` is refused the same way by every subcommand that takes it, before anything
/// runs (no device, display or asset needed).
#[test]
fn zero_frames_is_refused_everywhere() {
    for sub in ["render", "bench", "table", "sweep", "reference", "view"] {
        let mut cmd = ssgi();
        cmd.arg(sub);
        if sub == "table" {
            cmd.arg("thesis-4.1");
        }
        let out = cmd.args(["--frames", "0"]).output().unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{sub}: {stderr}");
        assert!(
            stderr.contains("--frames must be at least 1"),
            "{sub}: {stderr}"
        );
    }
}

/// `table --set` takes only the keys a table lets change, with `--vary`'s value checks, before
/// anything runs (no device needed).
#[test]
fn table_set_is_refused_where_the_table_does_not_take_it() {
    for (table, set, reason) in [
        (
            "thesis-4.1",
            "svgf.alpha=0.1",
            "table thesis-4.1 takes no --set keys (its rows set every parameter they use); the \
             tables that take --set: chang-flicker: svgf.*, ccipca.*; ao: ao.samples, \
             ao.steps, ao.position_mips, ao.moving_denoise",
        ),
        (
            "chang-flicker",
            "indirect.vpls=3",
            "table chang-flicker sets indirect.vpls itself or does not use it: its --set keys \
             are svgf.*, ccipca.*",
        ),
        ("chang-flicker", "svgf.alpha=2", "--set svgf.alpha=2: "),
        (
            "chang-flicker",
            "svgf.alpha",
            "--set takes KEY=VALUE, not \"svgf.alpha\"",
        ),
        ("ao", "ao.radius=0.5", "table ao sets ao.radius itself"),
        ("ao", "no.such=1", "--set \"no.such\": no such key"),
    ] {
        let out = ssgi()
            .args(["table", table, "--set", set])
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{table} --set {set}");
        assert!(stderr.contains(reason), "{table} --set {set}: {stderr}");
    }
    let out = ssgi()
        .args(["table", "ao", "--set", "ao.steps=4", "--set", "ao.steps=8"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("--set ao.steps is given twice"), "{stderr}");
}

/// `bench --compare-reuse --json` writes docs/formats.md's compare-reuse format (both runs in the
/// bench format, the groups' ratios).
#[test]
fn compare_reuse_json_follows_its_documented_format() {
    let json = tmp("compare-reuse.json");
    let out = ssgi()
        .args([
            "--validation",
            "bench",
            "--compare-reuse",
            "--scene",
            "cornell-box",
        ])
        .args([
            "--size",
            "32x32",
            "--rsm-size",
            "64",
            "--effects",
            "direct,ao",
        ])
        .args(["--frames", "2", "--warmup", "1", "--json"])
        .arg(&json)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "bench failed:\n{stderr}");
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    schema::assert_follows("compare-reuse", &report);
    assert_eq!(report["runs"].as_array().map(Vec::len), Some(2));
    // The check can fail: a report without a documented key departs from docs/formats.md.
    let mut broken = report.clone();
    broken["runs"][1]["total"]
        .as_object_mut()
        .unwrap()
        .remove("p95_ms");
    broken["groups"]["ao"]["undocumented"] = serde_json::json!(1);
    let errors = schema::check("compare-reuse", &broken);
    assert_eq!(errors.len(), 2, "{errors:#?}");
    assert!(errors[0].contains("runs[1].total.p95_ms"), "{errors:#?}");
}

/// `--light P:T` moves the spot: aimed at the floor from above it lights the floor, aimed
/// away from behind the back wall it leaves the room to the ambient light; bad values get clear errors.
#[test]
fn light_flag_places_the_spot() {
    let direct_mean = |light: &str| {
        let dir = tmp(&format!(
            "light-{}",
            light.replace([',', ':', '.', '-'], "_")
        ));
        let out = ssgi()
            .args(["--validation", "render", "--scene", "cornell-box"])
            .args(["--size", "32x32", "--rsm-size", "64", "--effects", "direct"])
            .args(["--frames", "1", "--light", light, "--out"])
            .arg(dir.join("out.png"))
            .arg("--dump-gbuffer")
            .arg(&dir)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(
            out.status.success(),
            "render --light {light} failed:\n{stderr}"
        );
        let img = image::open(dir.join("output.png")).unwrap().to_rgb8();
        img.pixels()
            .map(|p| p[0] as f64 + p[1] as f64 + p[2] as f64)
            .sum::<f64>()
            / (3.0 * 255.0 * img.pixels().len() as f64)
    };
    let down = direct_mean("0,1.9,0:0,0,0");
    // Behind the back wall, aimed away: the room keeps only the ambient light, wherever
    // exactly the light is.
    let away = direct_mean("0,1,-3:0,1,-10");
    let away_too = direct_mean("2,1,-4:2,1,-10");
    assert!((away - away_too).abs() < 1e-3, "{away} vs {away_too}");
    assert!(
        down > away + 0.05,
        "light aimed at the floor: {down} vs away {away}"
    );
    for (bad, needle) in [
        ("0,1,0", "POSITION:TARGET"),
        ("0,1:0,0,0", "x,y,z"),
        ("0,nan,0:0,0,0", "finite"),
        ("1,1,1:1,1,1", "same point"),
    ] {
        let out = ssgi()
            .args(["render", "--size", "8x8", "--frames", "1", "--light", bad])
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "--light {bad} accepted");
        assert!(stderr.contains(needle), "--light {bad}: {stderr}");
    }
}

/// Resource exhaustion (issue 16): every effect at the largest size, or the largest shadow
/// map, ends with a clear message and exit code 1, not a crash: on lavapipe an RGBA32F image
/// of 16384x16384 (4 GiB) is past the device's largest image (maxResourceSize, 4 GiB less a
/// MiB), which is said before the image is made and names it (issue 62: it was reported as
/// out of memory after a validation error); a device that takes it runs out of memory
/// instead.
#[test]
fn huge_sizes_fail_with_a_clear_limit_message() {
    for args in [
        ["--size", "16384x16384", "--rsm-size", "512"],
        ["--size", "64x64", "--rsm-size", "16384"],
    ] {
        let out = ssgi()
            .args(["--validation", "render", "--effects", "all"])
            .args(args)
            .arg("--out")
            .arg(tmp("huge.png"))
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{args:?}: {stderr}");
        let limit = stderr.contains("is past this device's largest image of that format");
        assert!(
            (limit || stderr.contains("out of device memory"))
                && stderr.contains("try a smaller --size"),
            "{args:?}: {stderr}"
        );
        assert!(!stderr.contains("VUID"), "{args:?}: {stderr}");
        assert!(!stderr.contains("panicked"), "{stderr}");
    }
}

/// `bench --explain-skips` prints the dependency table: the G-buffer follows the camera, AO
/// ignores the light, indirect light does not.
#[test]
fn explain_skips_prints_what_each_pass_follows() {
    let out = ssgi()
        .args(["bench", "--scene", "cornell-box", "--size", "16x16"])
        .args(["--frames", "1", "--warmup", "0", "--explain-skips"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8_lossy(&out.stdout);
    let row = |pass: &str| {
        text.lines()
            .find(|l| l.split_whitespace().next() == Some(pass))
            .unwrap_or_else(|| panic!("no {pass} row in:\n{text}"))
            .to_string()
    };
    assert!(row("gbuffer").contains("camera"));
    assert!(row("light_view").contains("light"));
    assert!(!row("ssao").contains("light"), "{}", row("ssao"));
    assert!(row("ssao").contains("converges"));
    assert!(row("indirect_gather").contains("light"));
}

/// `bench --flicker`: every measured frame after the first carries its difference from the
/// frame before, and the summary is their mean. Direct light with hard shadows on a static
/// view is the same every frame (0 exactly); CCIPCA's indirect light from 4 new VPLs per
/// pixel each frame is not.
#[test]
fn bench_flicker_measures_consecutive_frames() {
    let run = |name: &str, extra: &[&str]| -> serde_json::Value {
        let json = tmp(name);
        let out = ssgi()
            .args([
                "--validation",
                "bench",
                "--scene",
                "cornell-box",
                "--size",
                "32x32",
            ])
            .args([
                "--frames",
                "5",
                "--warmup",
                "1",
                "--pcf",
                "hard",
                "--flicker",
            ])
            .args(extra)
            .arg("--json")
            .arg(&json)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "bench failed:\n{stderr}");
        assert!(
            !stderr.contains("vulkan: ["),
            "validation messages:\n{stderr}"
        );
        let report: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
        schema::assert_follows("bench", &report);
        report
    };
    let per_frame = |r: &serde_json::Value| -> Vec<f64> {
        r["frames"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|f| f["warmup"] == false)
            .filter_map(|f| f["flicker"]["final_msd"].as_f64())
            .collect()
    };
    let direct = run(
        "flicker-direct.json",
        &["--effects", "direct", "--skip-unchanged", "off"],
    );
    assert_eq!(per_frame(&direct), [0.0; 4], "{}", direct["frames"]);
    assert_eq!(direct["flicker"]["frames_below"], 4);
    let ccipca = run(
        "flicker-ccipca.json",
        &[
            "--effects",
            "direct,indirect",
            "--indirect-filter",
            "ccipca",
            "--vpls",
            "4",
        ],
    );
    let f = per_frame(&ccipca);
    assert_eq!(f.len(), 4, "{}", ccipca["frames"]);
    assert!(f.iter().all(|v| *v > 0.0), "{f:?}");
    let mean = f.iter().sum::<f64>() / 4.0;
    let reported = ccipca["flicker"]["final_msd_mean"].as_f64().unwrap();
    assert!(
        (reported - mean).abs() <= 1e-12 * mean.max(1.0),
        "{reported} vs {mean}"
    );
    assert!(ccipca["flicker"]["indirect_msd_mean"].as_f64().unwrap() > 0.0);
}

/// `bench --explain` prints the frame as data from the passes' declarations, and
/// docs/ARCHITECTURE.md shows it for the default frame (the block after its
/// `<!-- bench --explain -->` marker is this output, word for word). Independently of the
/// document: the second frame leaves the light view out (the light did not change), draws the
/// G-buffer before the reprojection reads it, and the composite writes the output last.
#[test]
fn bench_explain_prints_the_frame_the_architecture_doc_shows() {
    let out = ssgi()
        .args(["--validation", "bench", "--explain", "--size", "64x64"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "bench --explain failed:\n{stderr}");
    let text = String::from_utf8(out.stdout).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let at = |pass: &str| {
        lines
            .iter()
            .position(|l| l.split_whitespace().next() == Some(pass))
            .unwrap_or_else(|| panic!("no {pass} line in:\n{text}"))
    };
    assert!(
        lines[at("light_view")].ends_with("skipped (unchanged)"),
        "{text}"
    );
    assert!(at("gbuffer") < at("reproject") && at("reproject") < at("composite"));
    assert!(
        lines[at("gbuffer")].contains("writes gbuffer.position."),
        "{text}"
    );
    assert!(
        lines[at("reproject")].contains("gbuffer.position."),
        "{text}"
    );
    assert!(lines[at("composite")].contains("writes output"), "{text}");
    let doc = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/ARCHITECTURE.md"))
        .unwrap();
    let block = doc
        .split("<!-- bench --explain -->\n```\n")
        .nth(1)
        .and_then(|rest| rest.split("```").next())
        .expect("docs/ARCHITECTURE.md: a ``` block after <!-- bench --explain -->");
    assert_eq!(
        block, text,
        "docs/ARCHITECTURE.md's frame differs from `ssgi bench --explain --size 64x64`"
    );
}
