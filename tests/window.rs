//! The window frontend under X11 (Xvfb) on lavapipe, with validation + synchronization
//! validation: scripted resizes (down to 1x1), a zero extent, buffer display cycling, quitting
//! by key; the presented image against the headless render of the same frame; and
//! `bench --window`'s report. The runs use the binary's hidden `--script` and `--capture`
//! flags.
//!
//! X11 never reports a zero extent (a minimised X window keeps its size and a 0x0 window is
//! invalid; Xvfb has no window manager to minimise with), so the zero-extent step is simulated
//! by the frontend (`zero=N`: it behaves as if the surface had a zero extent for N event-loop
//! iterations, then recreates the swapchain).
//!
//! The tests use `$DISPLAY` when set (tools/test starts Xvfb); otherwise they start their own
//! Xvfb on a free display number. With neither a display nor Xvfb they fail, naming what is
//! missing (a test that cannot run must not count as passed).

#[path = "common/schema.rs"]
mod schema;

use std::io::{BufRead, BufReader};
use std::path::PathBuf;
use std::process::{Child, Command, Output, Stdio};

/// An X display for the test: `$DISPLAY`, or a private Xvfb killed on drop.
struct Display {
    name: String,
    xvfb: Option<Child>,
}

impl Drop for Display {
    fn drop(&mut self) {
        if let Some(child) = &mut self.xvfb {
            let _ = child.kill();
            let _ = child.wait();
        }
    }
}

fn display() -> Display {
    if let Some(name) = std::env::var("DISPLAY").ok().filter(|d| !d.is_empty()) {
        return Display { name, xvfb: None };
    }
    // -displayfd: Xvfb picks a free display number and writes it to stdout when ready.
    let spawned = Command::new("Xvfb")
        .args([
            "-displayfd",
            "1",
            "-screen",
            "0",
            "1024x768x24",
            "-nolisten",
            "tcp",
        ])
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn();
    let mut child = match spawned {
        Ok(c) => c,
        // A window test fails, never skips, without a display.
        Err(e) => panic!(
            "DISPLAY is not set and Xvfb could not be started ({e}); install xvfb \
             (tools/setup-vulkan does) or run tools/test"
        ),
    };
    let mut line = String::new();
    let stdout = child.stdout.take().expect("piped stdout");
    BufReader::new(stdout)
        .read_line(&mut line)
        .expect("Xvfb display number");
    let number: u32 = line
        .trim()
        .parse()
        .unwrap_or_else(|_| panic!("Xvfb printed {line:?} instead of a display number"));
    Display {
        name: format!(":{number}"),
        xvfb: Some(child),
    }
}

fn ssgi(display: &Display, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_ssgi"))
        .args(args)
        .env("DISPLAY", &display.name)
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .expect("run ssgi")
}

/// `ssgi --validation view --size SIZE --rsm-size 128 --frames FRAMES` and `extra`.
fn view(display: &Display, size: &str, frames: &str, extra: &[&str]) -> Output {
    let mut args = vec![
        "--validation",
        "view",
        "--size",
        size,
        "--rsm-size",
        "128",
        "--frames",
        frames,
    ];
    args.extend(extra);
    ssgi(display, &args)
}

/// The reason the command line gives for refusing `args` (clap's first line, after the
/// option's name).
fn cli_reason(args: &[&str]) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_ssgi"))
        .args(args)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    err.lines()
        .next()
        .and_then(|l| l.split_once("': "))
        .map(|(_, why)| why.to_string())
        .unwrap_or_else(|| panic!("no reason in {err}"))
}

fn tmp(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("ssgi-window-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// Success, no validation message (including leaks reported at device destruction, which are
/// printed after the exit status is decided), no panic.
fn assert_clean_run(out: &Output, what: &str) -> String {
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(out.status.success(), "{what} failed:\n{stderr}");
    assert!(
        !stderr.contains("vulkan: ["),
        "{what}: validation messages:\n{stderr}"
    );
    assert!(!stderr.contains("panicked"), "{what} panicked:\n{stderr}");
    stderr
}

#[test]
fn resize_minimise_cycle_and_close_are_validation_clean() {
    let display = display();
    let script = [
        "4:key=cycle", // direct
        "5:key=cycle", // shadow
        "6:key=cycle", // ao
        "7:key=cycle", // indirect
        "8:key=cycle", // normal
        "10:resize=96x72",
        "12:key=cycle", // albedo
        "14:key=cycle", // position
        "16:key=pcf",
        "18:resize=8x8",
        "22:zero=15",
        "26:key=cycle", // final
        "27:display=ao",
        "28:resize=1x1",
        "32:resize=40x56",
    ]
    .join(",");
    let out = ssgi(
        &display,
        &[
            "--validation",
            "view",
            "--size",
            "64x64",
            "--rsm-size",
            "128",
            "--frames",
            "40",
            "--script",
            &script,
        ],
    );
    let stderr = assert_clean_run(&out, "view");
    for expected in [
        "swapchain: 64x64",
        "swapchain: 96x72",
        "swapchain: 8x8",
        "swapchain: 1x1",
        "swapchain: 40x56",
        "present mode fifo",
        "window minimised (zero extent): rendering paused",
        "window restored: rendering resumed",
        "display: shadow",
        "display: indirect",
        "display: normal",
        "display: position",
        "display: final",
        "display: ao",
        "effects: -pcf",
        "presented 40 frames",
    ] {
        assert!(
            stderr.contains(expected),
            "expected {expected:?} in:\n{stderr}"
        );
    }
    // Rendering paused for the zero extent and resumed (with a new swapchain) after it.
    let paused = stderr.find("rendering paused").unwrap();
    let resumed = stderr.find("rendering resumed").unwrap();
    assert!(paused < resumed);
}

#[test]
fn quit_key_exits_cleanly_without_a_frame_limit() {
    let display = display();
    let out = ssgi(
        &display,
        &[
            "--validation",
            "view",
            "--size",
            "48x48",
            "--rsm-size",
            "128",
            "--script",
            "5:key=help,9:key=quit",
        ],
    );
    let stderr = assert_clean_run(&out, "view");
    assert!(stderr.contains("presented 9 frames"), "{stderr}");
    assert!(stderr.contains("ssgi view keys"), "help printed:\n{stderr}");
}

/// `ssgi --validation render` of the built-in scene at `size` for `frames` frames (RSM 128,
/// plus `extra` flags), validation-clean; the image written to `name`.
fn headless_render(size: &str, frames: &str, extra: &[&str], name: &str) -> image::RgbaImage {
    let path = tmp(name);
    let out = Command::new(env!("CARGO_BIN_EXE_ssgi"))
        .args([
            "--validation",
            "render",
            "--size",
            size,
            "--rsm-size",
            "128",
            "--frames",
            frames,
        ])
        .args(extra)
        .arg("--out")
        .arg(&path)
        .output()
        .unwrap();
    assert_clean_run(&out, "render");
    load_rgba(&path)
}

fn load_rgba(path: &PathBuf) -> image::RgbaImage {
    image::open(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .to_rgba8()
}

/// Pixels whose channels differ by more than 2/255 (images of equal size).
fn differing_pixels(a: &image::RgbaImage, b: &image::RgbaImage) -> usize {
    a.pixels()
        .zip(b.pixels())
        .filter(|(p, q)| (0..4).any(|c| (p[c] as i32 - q[c] as i32).abs() > 2))
        .count()
}

#[test]
fn displayed_buffer_is_the_headless_g_buffer() {
    let display = display();
    let shot = tmp("albedo-presented.png");
    let dump = tmp("albedo-dump");
    let common = ["--size", "64x48", "--rsm-size", "128", "--frames", "3"];
    let mut args = vec!["--validation", "view", "--overlay", "off"];
    args.extend(common);
    args.extend(["--script", "0:display=albedo", "--capture"]);
    args.push(shot.to_str().unwrap());
    let out = ssgi(&display, &args);
    let stderr = assert_clean_run(&out, "view --capture");
    assert!(stderr.contains("display: albedo\n"), "{stderr}");
    let final_png = dump.join("final.png");
    let mut args = vec!["--validation", "render"];
    args.extend(common);
    args.extend(["--out", final_png.to_str().unwrap(), "--dump-gbuffer"]);
    args.push(dump.to_str().unwrap());
    let out = Command::new(env!("CARGO_BIN_EXE_ssgi"))
        .args(&args)
        .output()
        .unwrap();
    assert_clean_run(&out, "render --dump-gbuffer");
    let shot = load_rgba(&shot);
    let albedo = load_rgba(&dump.join("gbuffer_albedo.png"));
    let lit = load_rgba(&final_png);
    assert_eq!(shot.dimensions(), albedo.dimensions());
    let total = (shot.width() * shot.height()) as usize;
    let bad = differing_pixels(&shot, &albedo);
    assert!(
        bad * 1000 <= total,
        "{bad} of {total} pixels of the displayed albedo differ from the dumped G-buffer albedo"
    );
    // And it is not the final image (the buffer choice reached the renderer).
    assert!(differing_pixels(&shot, &lit) * 4 > total);
}

#[test]
fn presented_frame_matches_the_headless_render() {
    let display = display();
    let (size, frames) = ("64x48", "6");
    let shot = tmp("presented.png");
    let out = ssgi(
        &display,
        &[
            "--validation",
            "view",
            "--overlay",
            "off",
            "--size",
            size,
            "--rsm-size",
            "128",
            "--frames",
            frames,
            "--capture",
            shot.to_str().unwrap(),
        ],
    );
    assert_clean_run(&out, "view --capture");
    let (a, b) = (
        load_rgba(&shot),
        headless_render(size, frames, &[], "headless.png"),
    );
    assert_eq!(a.dimensions(), (64, 48));
    assert_eq!(a.dimensions(), b.dimensions());
    // The picture is not trivially flat (a black or cleared swapchain would fail here).
    let lum: Vec<u32> = b
        .pixels()
        .map(|p| p[0] as u32 + p[1] as u32 + p[2] as u32)
        .collect();
    let (lo, hi) = (lum.iter().min().unwrap(), lum.iter().max().unwrap());
    assert!(hi - lo > 100, "reference image is flat ({lo}..{hi})");
    // Red left wall, green right wall.
    let sums = |x0: u32, x1: u32| {
        let mut rgb = [0u64; 3];
        for (x, _, p) in a.enumerate_pixels() {
            if (x0..x1).contains(&x) {
                for c in 0..3 {
                    rgb[c] += p[c] as u64;
                }
            }
        }
        rgb
    };
    let (left, right) = (sums(0, 21), sums(43, 64));
    // (A BGRA/RGBA swap would turn the red wall blue.)
    let dominant = |rgb: [u64; 3], c: usize| (0..3).all(|o| o == c || rgb[c] * 5 > rgb[o] * 6);
    assert!(
        dominant(left, 0) && dominant(right, 1),
        "left third {left:?} should be red, right third {right:?} green"
    );
    let total = (a.width() * a.height()) as usize;
    let bad = differing_pixels(&a, &b);
    assert!(
        bad * 1000 <= total,
        "{bad} of {total} pixels differ by more than 2/255 from the headless render"
    );
}

#[test]
fn bench_window_reports_the_present_mode() {
    let display = display();
    let json = tmp("bench-window.json");
    let out = ssgi(
        &display,
        &[
            "--validation",
            "bench",
            "--window",
            "--size",
            "48x48",
            "--rsm-size",
            "128",
            "--path",
            "orbit",
            "--frames",
            "5",
            "--warmup",
            "1",
            "--json",
            json.to_str().unwrap(),
        ],
    );
    let stderr = assert_clean_run(&out, "bench --window");
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    schema::assert_follows("bench", &report);
    assert_eq!(report["config"]["window"], true);
    let mode = report["config"]["present_mode"].as_str().unwrap();
    assert!(
        ["immediate", "mailbox", "fifo"].contains(&mode),
        "present mode {mode}"
    );
    assert!(
        stderr.contains(&format!("present mode for benchmarking: {mode}")),
        "{stderr}"
    );
    let frames = report["frames"].as_array().unwrap();
    assert_eq!(frames.len(), 6);
    assert_eq!(report["measured_frames"], 5);
    // Every frame is listed; the warmup one is marked.
    let warmup: Vec<bool> = frames.iter().map(|f| f["warmup"] == true).collect();
    assert_eq!(warmup, [true, false, false, false, false, false]);
    assert!(report["total"]["median_ms"].as_f64().unwrap() > 0.0);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains("composite"), "{stdout}");
}

#[test]
fn view_without_a_display_fails_with_a_clear_error() {
    let out = Command::new(env!("CARGO_BIN_EXE_ssgi"))
        .args(["view", "--frames", "1"])
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .env_remove("WAYLAND_SOCKET")
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(stderr.contains("cannot open a window"), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
}

/// Run `ssgi --validation --assets A table thesis-walkthroughs` at 32x32 with `extra` flags;
/// returns report.json and stderr.
fn walkthrough_table(
    display: &Display,
    assets: &std::path::Path,
    out: &std::path::Path,
    extra: &[&str],
) -> (serde_json::Value, String) {
    let mut args = vec![
        "--validation",
        "--assets",
        assets.to_str().unwrap(),
        "table",
        "thesis-walkthroughs",
        "--size",
        "32x32",
        "--frames",
        "3",
        "--warmup",
        "2",
        "--effects",
        "direct,ao",
        "--out",
        out.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    let run = ssgi(display, &args);
    let stderr = assert_clean_run(&run, &format!("table {extra:?}"));
    let text = std::fs::read_to_string(out.join("report.json")).unwrap();
    let report = serde_json::from_str(&text).unwrap();
    schema::assert_follows("thesis-table", &report);
    (report, stderr)
}

/// `table --window` presents every frame of every row (reference, reuse, no reuse) of every
/// scene through one window, and presenting changes nothing in the rendered buffers: each
/// row's error against its reference is the one of the same table run offscreen.
#[test]
fn table_window_presents_every_row_and_matches_offscreen() {
    let display = display();
    let assets = std::env::var_os("SSGI_ASSETS")
        .filter(|v| !v.is_empty())
        .unwrap_or_else(|| panic!("SSGI_ASSETS is not set: this test needs the papers' models (the shared scenes directory, ../shared/scenes in this workspace); tools/test sets it"));
    let assets = PathBuf::from(assets);
    let (windowed, stderr) =
        walkthrough_table(&display, &assets, &tmp("table-window"), &["--window"]);
    let (offscreen, _) = walkthrough_table(&display, &assets, &tmp("table-offscreen"), &[]);
    assert_eq!(windowed["window"], true);
    assert_eq!(offscreen["window"], false);
    assert!(offscreen["present_mode"].is_null());
    let mode = windowed["present_mode"].as_str().unwrap();
    assert!(
        ["immediate", "mailbox", "fifo"].contains(&mode),
        "present mode {mode}"
    );
    let scenes = windowed["scenes"].as_array().unwrap();
    assert_eq!(scenes.len(), 3);
    let mut expected_frames = 0;
    for (s, o) in scenes.iter().zip(offscreen["scenes"].as_array().unwrap()) {
        let rows = s["rows"].as_array().unwrap();
        assert_eq!(rows.len(), 3, "{}", s["name"]);
        for (r, ro) in rows.iter().zip(o["rows"].as_array().unwrap()) {
            assert_eq!(r["kind"], ro["kind"]);
            assert_eq!(r["report"]["config"]["present_mode"], mode);
            expected_frames +=
                r["measured_frames"].as_u64().unwrap() + r["warmup"].as_u64().unwrap();
            let errors = r["error"].as_object().unwrap();
            assert!(!errors.is_empty());
            for (buffer, e) in errors {
                for key in ["rmse", "max_abs"] {
                    let (a, b) = (
                        e[key].as_f64().unwrap(),
                        ro["error"][buffer][key].as_f64().unwrap(),
                    );
                    assert!(
                        (a - b).abs() <= 1e-9,
                        "{} {} {buffer} {key}: window {a} vs offscreen {b}",
                        s["name"],
                        r["kind"]
                    );
                }
            }
        }
    }
    assert!(
        stderr.contains(&format!("presented {expected_frames} frames to the window")),
        "expected {expected_frames} presented frames:\n{stderr}"
    );
}

/// The AO and reuse keys rebuild the renderer: after switching AO off and reuse off at frame 2,
/// the presented image is the headless render of the new configuration over the remaining
/// frames (histories start over), and not the one of the starting configuration.
#[test]
fn effect_keys_rebuild_the_renderer() {
    let display = display();
    let size = "64x48";
    let shot = tmp("toggled.png");
    let out = ssgi(
        &display,
        &[
            "--validation",
            "view",
            "--overlay",
            "off",
            "--size",
            size,
            "--rsm-size",
            "128",
            "--frames",
            "6",
            "--script",
            "2:key=ao,2:key=reuse",
            "--capture",
            shot.to_str().unwrap(),
        ],
    );
    let stderr = assert_clean_run(&out, "view with effect keys");
    assert!(
        stderr.contains("renderer rebuilt: pcf -ao indirect -ssdo -normals filter -reuse"),
        "{stderr}"
    );
    let switched = headless_render(
        size,
        "4",
        &["--effects", "direct,indirect", "--reuse", "off"],
        "toggled-ref.png",
    );
    let unswitched = headless_render(size, "6", &[], "untoggled-ref.png");
    let shot = load_rgba(&shot);
    let total = (shot.width() * shot.height()) as usize;
    let bad = differing_pixels(&shot, &switched);
    assert!(
        bad * 1000 <= total,
        "{bad} of {total} pixels differ from the headless render of the switched configuration"
    );
    assert!(
        differing_pixels(&shot, &unswitched) * 50 > total,
        "the switches did not change the picture"
    );
}

/// The overlay is drawn in the frame and nowhere else: a capture with it differs from one
/// with `--overlay off` only inside the rectangle the viewer reports for it, and it does
/// differ there (text and bars over a dimmed frame). `H` (the script's `key=overlay`) hides it:
/// the capture then equals the one without.
#[test]
fn overlay_changes_only_its_rectangle() {
    let display = display();
    let run = |name: &str, extra: &[&str]| {
        let shot = tmp(name);
        // Direct light only: a short list of passes, so the panel leaves part of the
        // 320x240 frame uncovered.
        let mut args = vec!["--effects", "direct", "--capture", shot.to_str().unwrap()];
        args.extend(extra);
        let out = view(&display, "320x240", "4", &args);
        let stderr = assert_clean_run(&out, &format!("view {extra:?}"));
        (load_rgba(&shot), stderr)
    };
    let (with, stderr) = run("overlay-on.png", &[]);
    let (without, _) = run("overlay-off.png", &["--overlay", "off"]);
    let (hidden, hidden_err) = run("overlay-hidden.png", &["--script", "1:key=overlay"]);
    assert!(hidden_err.contains("overlay: hidden"), "{hidden_err}");
    let line = stderr
        .lines()
        .find_map(|l| l.strip_prefix("overlay rectangle: "))
        .unwrap_or_else(|| panic!("no overlay rectangle reported:\n{stderr}"));
    let r: Vec<u32> = line
        .split_whitespace()
        .take(4)
        .map(|v| v.parse().expect("rectangle coordinate"))
        .collect();
    let (x0, y0, x1, y1) = (r[0], r[1], r[2], r[3]);
    assert!(x0 < x1 && y0 < y1 && x1 <= 320 && y1 <= 240, "{line}");
    let area = ((x1 - x0) * (y1 - y0)) as usize;
    assert!(
        area < 320 * 240,
        "the overlay covers the whole frame: {line}"
    );
    let (mut inside, mut outside) = (0usize, Vec::new());
    for (x, y, p) in with.enumerate_pixels() {
        let q = without.get_pixel(x, y);
        if (0..3).any(|c| p[c] != q[c]) {
            if (x0..x1).contains(&x) && (y0..y1).contains(&y) {
                inside += 1;
            } else {
                outside.push((x, y));
            }
        }
    }
    assert!(
        outside.is_empty(),
        "{} pixels outside the overlay rectangle {line} differ, first {:?}",
        outside.len(),
        &outside[..outside.len().min(5)]
    );
    assert!(
        inside * 2 > area,
        "only {inside} of the rectangle's {area} pixels changed: is the overlay drawn?"
    );
    assert_eq!(
        differing_pixels(&hidden, &without),
        0,
        "a hidden overlay still changes the frame"
    );
}

/// The overlay fits what it overlays: with every effect on, in a 320x240 window it shows its
/// compact summary, which covers less than half of the frame (the full panel covered 87.5%);
/// O (the script's `key=panel`) brings the full panel, which covers more.
#[test]
fn overlay_fits_a_small_window() {
    let display = display();
    let run = |name: &str, extra: &[&str]| {
        let shot = tmp(name);
        let mut args = vec!["--capture", shot.to_str().unwrap()];
        args.extend(extra);
        let out = view(&display, "320x240", "4", &args);
        let stderr = assert_clean_run(&out, &format!("view {extra:?}"));
        (load_rgba(&shot), stderr)
    };
    let (without, _) = run("small-overlay-off.png", &["--overlay", "off"]);
    let (compact, _) = run("small-overlay-compact.png", &[]);
    let (full, full_err) = run("small-overlay-full.png", &["--script", "1:key=panel"]);
    assert!(full_err.contains("overlay: full panel"), "{full_err}");
    let total = 320 * 240;
    let covered = differing_pixels(&compact, &without);
    let covered_full = differing_pixels(&full, &without);
    eprintln!("overlay over 320x240: compact {covered} pixels, full {covered_full}");
    assert!(covered > 0, "no overlay drawn");
    assert!(
        covered * 2 < total,
        "the compact overlay covers {covered} of {total} pixels"
    );
    assert!(
        covered_full > covered,
        "O did not bring the full panel ({covered_full})"
    );
}

/// The screenshot key (F12; the script's `key=screenshot`) writes the presented frame, overlay
/// included, and the last second's timings as a bench report (docs/formats.md) with the
/// overlay's own timing row.
#[test]
fn screenshot_key_writes_the_frame_and_a_bench_report() {
    let display = display();
    let dir = tmp("shots");
    let shot = tmp("shot-capture.png");
    let out = view(
        &display,
        "160x120",
        "4",
        &[
            "--script",
            "3:key=screenshot",
            "--screenshot-dir",
            dir.to_str().unwrap(),
            "--capture",
            shot.to_str().unwrap(),
        ],
    );
    let stderr = assert_clean_run(&out, "view with the screenshot key");
    assert!(stderr.contains("screenshot: wrote"), "{stderr}");
    // The key fired before the fourth frame, which --capture also reads back.
    let png = load_rgba(&dir.join("view-000004.png"));
    assert_eq!(differing_pixels(&png, &load_rgba(&shot)), 0);
    let text = std::fs::read_to_string(dir.join("view-000004.json")).expect("report");
    let report: serde_json::Value = serde_json::from_str(&text).expect("JSON");
    schema::assert_follows("bench", &report);
    assert_eq!(report["config"]["path"], "view (fly camera)");
    assert_eq!(
        (report["width"].as_u64(), report["height"].as_u64()),
        (Some(160), Some(120))
    );
    let overlay = report["passes"]
        .as_array()
        .unwrap()
        .iter()
        .find(|p| p["name"] == "overlay")
        .unwrap_or_else(|| panic!("no overlay row:\n{text}"));
    assert!(
        overlay["median_ms"].as_f64().is_some_and(|ms| ms > 0.0),
        "{overlay}"
    );
}

/// A live setting (the overlay's controls; the script's `set=KEY:VALUE`) goes through the
/// command line's parser: switching the AO estimator and the indirect filter gives the
/// configuration and records exactly the passes a headless run with `--ao gtao
/// --indirect-filter svgf` does, and a refused value prints the command line's reason and
/// changes nothing.
#[test]
fn live_settings_match_the_command_line() {
    let display = display();
    let dir = tmp("settings-shots");
    let out = view(
        &display,
        "64x48",
        "6",
        &[
            "--skip-unchanged",
            "off",
            "--script",
            "1:set=indirect.vpls:0,2:set=ao.estimator:gtao,2:set=indirect.filter:svgf,5:key=screenshot",
            "--screenshot-dir",
            dir.to_str().unwrap(),
        ],
    );
    let stderr = assert_clean_run(&out, "view with live settings");
    // The refused value: the command line's own reason.
    let why = cli_reason(&["render", "--vpls", "0"]);
    assert!(
        stderr.contains("cannot set indirect.vpls=0: ") && stderr.contains(&why),
        "the viewer did not print the command line's reason {why:?}:\n{stderr}"
    );
    assert!(
        stderr.contains("renderer rebuilt: ao.estimator=gtao"),
        "{stderr}"
    );
    let report: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(dir.join("view-000006.json")).expect("screenshot report"),
    )
    .unwrap();
    let recorded = |r: &serde_json::Value| -> Vec<String> {
        r["passes"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|p| p["recorded"].as_u64() > Some(0) && p["name"] != "overlay")
            .map(|p| p["name"].as_str().unwrap().to_string())
            .collect()
    };
    let json = tmp("settings-bench.json");
    let bench = Command::new(env!("CARGO_BIN_EXE_ssgi"))
        .args([
            "--validation",
            "bench",
            "--size",
            "64x48",
            "--rsm-size",
            "128",
            "--skip-unchanged",
            "off",
            "--ao",
            "gtao",
            "--indirect-filter",
            "svgf",
            "--frames",
            "3",
            "--warmup",
            "0",
            "--json",
            json.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert_clean_run(&bench, "bench --ao gtao");
    let headless: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert_eq!(report["config"]["render"], headless["config"]["render"]);
    assert_eq!(recorded(&report), recorded(&headless));
    assert!(recorded(&report).iter().any(|p| p == "svgf_temporal"));
}

/// The ground-truth key (G; the script's `key=truth`, then `wait=truth`) scores the frame on
/// screen as `ssgi reference` and the sweep's metric do: here the same frame is rendered
/// headless, the reference traced at `ssgi reference`'s default sample counts, and each
/// buffer's RMSE computed with `bench::ground_truth::errors`; they agree within 1e-6. The error
/// map key (M) then shows the final image's FLIP map the sweep writes
/// (`<stem>-final-flip.png`). A camera move while the tracer runs cancels it: no result is
/// printed.
#[test]
fn ground_truth_key_scores_like_the_reference_and_the_sweep() {
    use ssgi::bench::{ground_truth, measure::read_frame};
    use ssgi::cli::args::{Cli, Command as Job};
    use ssgi::reference::run::Session;
    use ssgi::reference::trace::{
        DEFAULT_AO_SAMPLES, DEFAULT_INDIRECT_SAMPLES, DEFAULT_SOFT_SHADOW_SAMPLES,
    };
    use ssgi::reference::{RefBuffer, Settings};

    let display = display();
    let cache = tmp("truth-cache");
    let args = ["--size", "48x36", "--rsm-size", "128"];
    let shot = tmp("truth-map.png");
    let run = |frames: &str, script: &str| {
        let mut all = vec![
            "--validation",
            "view",
            "--frames",
            frames,
            "--script",
            script,
        ];
        all.extend(args);
        all.extend(["--overlay", "off", "--capture", shot.to_str().unwrap()]);
        Command::new(env!("CARGO_BIN_EXE_ssgi"))
            .args(&all)
            .env("DISPLAY", &display.name)
            .env("SSGI_CACHE", &cache)
            .env_remove("WAYLAND_DISPLAY")
            .output()
            .expect("run ssgi")
    };
    // Cancelled: the camera moves on the frame after the tracer starts.
    let out = run("8", "3:key=truth,4:move=0.01");
    let stderr = assert_clean_run(&out, "view, ground truth cancelled");
    assert!(
        stderr.contains("ground truth cancelled: the camera moved"),
        "{stderr}"
    );
    assert!(!stderr.contains(" rmse "), "{stderr}");
    // Completed: 30 frames presented, then traced and scored.
    let out = run("32", "30:key=truth,30:wait=truth,30:key=errormap");
    let stderr = assert_clean_run(&out, "view, ground truth");
    let viewer: Vec<(String, f64)> = stderr
        .lines()
        .filter_map(|l| l.strip_prefix("ground truth: "))
        .filter_map(|l| {
            let mut w = l.split_whitespace();
            let name = w.next()?.to_string();
            (w.next()? == "rmse").then_some(())?;
            Some((name, w.next()?.parse().ok()?))
        })
        .collect();
    assert!(viewer.len() >= 4, "no RMSE lines:\n{stderr}");

    // The same frame headless, with the viewer's own configuration (the command line's).
    let cli = <Cli as clap::Parser>::parse_from(["ssgi", "view"].into_iter().chain(args));
    let Job::View(view_args) = &cli.command else {
        unreachable!()
    };
    let config = view_args.scene.render_config();
    let scene = ssgi::scene::load_scene("cornell-box", None).unwrap();
    let ctx = ssgi::vk::Context::new(&ssgi::vk::ContextOptions {
        validation: true,
        ..Default::default()
    })
    .unwrap();
    let mut renderer = ssgi::renderer::Renderer::new(&ctx, scene.clone(), config).unwrap();
    let camera = scene.camera;
    for _ in 0..30 {
        renderer.render_frame(&camera).unwrap();
    }
    renderer.finish().unwrap();
    let last = read_frame(&mut renderer, camera).unwrap();
    // `ssgi reference`'s way: one refinement per buffer to its default count, no cache.
    let settings = Settings::for_render(&config, &scene);
    let mut session = Session::start(&scene, camera, 48, 36, settings, None, false).unwrap();
    session.ensure(RefBuffer::Ao, DEFAULT_AO_SAMPLES).unwrap();
    session
        .ensure(RefBuffer::Direct, DEFAULT_SOFT_SHADOW_SAMPLES)
        .unwrap();
    session
        .ensure(RefBuffer::Indirect, DEFAULT_INDIRECT_SAMPLES)
        .unwrap();
    let terms = ssgi::effects::estimated_terms(&config);
    let errors = ground_truth::errors(&last, &session.reference, &scene, terms).unwrap();
    assert_eq!(viewer.len(), errors.len(), "{stderr}");
    for (b, e) in &errors {
        let got = viewer
            .iter()
            .find(|(n, _)| n == b.name())
            .unwrap_or_else(|| panic!("no {} line:\n{stderr}", b.name()))
            .1;
        let want = e.error.rmse;
        assert!(
            (got - want).abs() <= 1e-6 * want.abs().max(1e-12),
            "{}: viewer {got:e}, reference + sweep metric {want:e}",
            b.name()
        );
    }
    let maps = tmp("truth-maps");
    std::fs::create_dir_all(&maps).unwrap();
    ground_truth::write_error_maps(&last, &session.reference, &scene, terms, &maps, "t").unwrap();
    let flip = load_rgba(&maps.join("t-final-flip.png"));
    assert_eq!(
        differing_pixels(&load_rgba(&shot), &flip),
        0,
        "the shown map is not the sweep's"
    );
    drop(renderer);
    ctx.wait_idle().unwrap();
}

/// The render scale (the overlay's setting, `--render-scale`): the renderer renders at that
/// fraction of the window and the window still shows the whole frame; a refused value gives
/// the command line's reason.
#[test]
fn render_scale_setting_resizes_the_renderer() {
    let display = display();
    let dir = tmp("scale-shots");
    let out = view(
        &display,
        "64x48",
        "4",
        &[
            "--script",
            "1:set=render_scale:2,1:set=render_scale:0.5,3:key=screenshot",
            "--screenshot-dir",
            dir.to_str().unwrap(),
        ],
    );
    let stderr = assert_clean_run(&out, "view with a render scale");
    let why = cli_reason(&["view", "--render-scale", "2"]);
    assert!(
        stderr.contains("cannot set render_scale=2: ") && stderr.contains(&why),
        "{stderr}"
    );
    let report: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(dir.join("view-000004.json")).expect("screenshot report"),
    )
    .unwrap();
    assert_eq!(
        (report["width"].as_u64(), report["height"].as_u64()),
        (Some(32), Some(24))
    );
    assert_eq!(
        load_rgba(&dir.join("view-000004.png")).dimensions(),
        (64, 48)
    );
}
