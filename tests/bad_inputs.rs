//! Issue 62's bad inputs (items 9-23) through the `ssgi` binary: each gets a clear error
//! naming the option or the file (or a correct result), before anything renders, never a
//! panic, a hang or exit 0 with a wrong result.

use std::path::PathBuf;
use std::process::{Command, Output};
use std::sync::mpsc;
use std::time::Duration;

/// Only a hung child is killed this late; no test measures time.
const HANG_LIMIT: Duration = Duration::from_secs(600);

fn ssgi() -> Command {
    Command::new(env!("CARGO_BIN_EXE_ssgi"))
}

/// A fresh scratch directory for one test.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("ssgi-bad-{}-{name}", std::process::id()));
    std::fs::remove_dir_all(&dir).ok();
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Run `cmd` to its end, killing it (by its unreaped pid) if it outlives [`HANG_LIMIT`].
fn run(mut cmd: Command) -> Output {
    let child = cmd
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let pid = child.id();
    let (done, waiting) = mpsc::channel::<()>();
    let watchdog = std::thread::spawn(move || {
        let hung = waiting.recv_timeout(HANG_LIMIT) == Err(mpsc::RecvTimeoutError::Timeout);
        if hung {
            Command::new("kill")
                .args(["-KILL", &pid.to_string()])
                .status()
                .ok();
        }
        hung
    });
    let out = child.wait_with_output().unwrap();
    drop(done);
    assert!(!watchdog.join().unwrap(), "{cmd:?} hung and was killed");
    out
}

/// `args` fail with every one of `needles` in the message, and without rendering (no device
/// was opened) unless `rendered` is allowed.
fn fails_before_rendering(args: &[&str], needles: &[&str]) -> String {
    let mut cmd = ssgi();
    cmd.args(args);
    let out = run(cmd);
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(!out.status.success(), "{args:?} should fail:\n{stderr}");
    assert_ne!(out.status.code(), Some(101), "{args:?} panicked:\n{stderr}");
    for needle in needles {
        assert!(
            stderr.contains(needle),
            "{args:?}: no {needle:?} in:\n{stderr}"
        );
    }
    assert!(!stderr.contains("panicked"), "{args:?}:\n{stderr}");
    assert!(
        !stderr.contains("device: "),
        "{args:?} opened the device before failing:\n{stderr}"
    );
    stderr
}

/// Item 9: a FIFO given as the scene, a path or a light path is refused before it is opened
/// (opening it would block until something writes to it).
#[test]
fn a_fifo_is_refused_where_a_file_is_read() {
    let dir = scratch("fifo");
    for name in ["scene.obj", "scene.toml", "path.json"] {
        let status = Command::new("mkfifo").arg(dir.join(name)).status().unwrap();
        assert!(status.success(), "mkfifo {name}");
    }
    let arg = |name: &str| dir.join(name).to_str().unwrap().to_string();
    let fifo = "FIFO (named pipe)";
    fails_before_rendering(
        &["render", "--scene", &arg("scene.obj")],
        &["scene.obj", fifo],
    );
    fails_before_rendering(
        &["render", "--scene", &arg("scene.toml")],
        &["scene.toml", fifo],
    );
    fails_before_rendering(
        &["render", "--path", &arg("path.json")],
        &["camera path", "path.json", fifo],
    );
    // Item 19: a light path's error says "light path".
    fails_before_rendering(
        &["render", "--light-path", &arg("path.json")],
        &["light path", "path.json", fifo],
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// Item 19: what a path is, when it is not what the option takes.
#[test]
fn a_path_of_the_wrong_kind_says_what_it_is() {
    let dir = scratch("kinds");
    let file = dir.join("plain");
    std::fs::write(&file, "x").unwrap();
    fails_before_rendering(
        &[
            "--assets",
            file.to_str().unwrap(),
            "render",
            "--scene",
            "bunny",
        ],
        &["is a regular file, not a directory"],
    );
    fails_before_rendering(
        &["render", "--scene", "/dev/zero"],
        &["/dev/zero is a character device, not a model file"],
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// Items 11, 13 and 18: every output is checked before anything renders, and the error
/// names the option and the user's path (not a temporary file).
#[test]
fn outputs_are_checked_before_rendering() {
    let dir = scratch("outputs");
    let file = dir.join("plain");
    std::fs::write(&file, "x").unwrap();
    let file = file.to_str().unwrap();
    let under_file = format!("{file}/x.png");
    let e = fails_before_rendering(
        &["render", "--size", "8x8", "--out", "/proc/x.png"],
        &["--out /proc/x.png: cannot write there"],
    );
    assert!(!e.contains(".tmp-"), "{e}");
    fails_before_rendering(
        &["render", "--size", "8x8", "--out", &under_file],
        &["--out", "plain is a regular file, not a directory"],
    );
    fails_before_rendering(
        &["render", "--size", "8x8", "--out", "x.jpg"],
        &["--out x.jpg: ssgi writes PNG images only"],
    );
    fails_before_rendering(
        &["render", "--size", "8x8", "--dump-gbuffer", file],
        &["--dump-gbuffer", "it is a regular file, not a directory"],
    );
    fails_before_rendering(
        &["bench", "--size", "8x8", "--json", "/proc/r.json"],
        &["--json /proc/r.json: cannot write there"],
    );
    fails_before_rendering(
        &["stress", "--quick", "--out", file],
        &["--out", "it is a regular file, not a directory"],
    );
    fails_before_rendering(
        &["sweep", "--size", "8x8", "--out", "/proc/sweep"],
        &["--out /proc/sweep: cannot create it"],
    );
    fails_before_rendering(
        &["reference", "--size", "8x8", "--out", file],
        &["--out", "it is a regular file, not a directory"],
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// Item 12: a spherical light larger than the scene is refused (its shadow rays would find
/// no occluder: a lit, noiseless shadow buffer), naming the option and the bound.
#[test]
fn a_light_larger_than_the_scene_is_refused() {
    let dir = scratch("light-radius");
    for radius in ["1e7", "1e30"] {
        fails_before_rendering(
            &[
                "reference",
                "--size",
                "8x8",
                "--no-cache",
                "--light-radius",
                radius,
                "--out",
                dir.to_str().unwrap(),
            ],
            &["--light-radius", "larger than the scene's bounding radius"],
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// Item 15: a light far too bright for the scene is refused on the command line as in a
/// scene file (src/scene/scene_load.rs tests that), with the bound for the scene's size.
#[test]
fn a_light_too_bright_for_the_scene_is_refused() {
    fails_before_rendering(
        &["render", "--size", "8x8", "--light-intensity", "1e30"],
        &[
            "--light-intensity [1e30, 1e30, 1e30] W/sr is more than",
            "bounding radius",
        ],
    );
}

/// Item 14: `bench --explain` writes nothing, so a file to write is an error.
#[test]
fn explain_refuses_outputs_it_would_not_write() {
    for option in [["--json", "f.json"], ["--out", "f.png"]] {
        fails_before_rendering(
            &["bench", "--explain", option[0], option[1]],
            &["--explain", &format!("leave out {}", option[0])],
        );
    }
}

/// Item 14: an option of an effect the run leaves off changes nothing: the run warns and
/// renders.
#[test]
fn options_of_an_effect_that_is_off_are_a_warning() {
    let dir = scratch("unused");
    let png = dir.join("r.png");
    let mut cmd = ssgi();
    cmd.args(["render", "--size", "16x16", "--effects", "direct,ao"])
        .args(["--ssdo-scale", "0.5", "--out"])
        .arg(&png);
    let out = run(cmd);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert_eq!(
        stderr
            .matches("warning: --ssdo-scale has no effect: ssdo is not in --effects")
            .count(),
        1,
        "{stderr}"
    );
    assert!(png.is_file());
    std::fs::remove_dir_all(&dir).ok();
}

/// Item 16: a negative number reaches the option's value parser, which names both.
#[test]
fn negative_numbers_name_their_option() {
    fails_before_rendering(&["render", "--frames", "-1"], &["--frames", "\"-1\""]);
    fails_before_rendering(&["render", "--fps", "-60"], &["--fps", "\"-60\""]);
    fails_before_rendering(
        &["render", "--light-intensity", "-1"],
        &["--light-intensity", "\"-1\""],
    );
}

/// Item 20: an argument that is not UTF-8 is named.
#[test]
fn a_non_utf8_argument_is_named() {
    use std::os::unix::ffi::OsStrExt;
    let mut cmd = ssgi();
    cmd.args(["render", "--scene"])
        .arg(std::ffi::OsStr::from_bytes(b"sc\xe8ne.obj"));
    let out = run(cmd);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(
        stderr.contains("argument 3 (the value of --scene) is not valid UTF-8"),
        "{stderr}"
    );
}
