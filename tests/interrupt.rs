//! Interrupting a long `ssgi table`: Ctrl-C (SIGINT) stops it cleanly (exit 130, a message, the
//! previous report untouched), and even SIGKILL, which nothing can catch, leaves the previous
//! report whole (reports are written atomically, temporary file + rename).

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};

const PREVIOUS: &str = "{\"previous\": true}\n";

/// The asset directory; the test fails (never skips) when SSGI_ASSETS is not set.
fn assets() -> PathBuf {
    ssgi::scene::asset_dir_from_env().unwrap_or_else(|| panic!("SSGI_ASSETS is not set: this test needs the papers' models (the shared scenes directory, ../shared/scenes in this workspace); tools/test sets it"))
}

fn out_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("ssgi-interrupt-{}-{name}", std::process::id()));
    std::fs::remove_dir_all(&dir).ok();
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("report.json"), PREVIOUS).unwrap();
    dir
}

/// A table far too long to finish, its stderr forwarded line by line.
fn start_table(out: &Path) -> (Child, mpsc::Receiver<String>) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_ssgi"))
        .arg("--assets")
        .arg(assets())
        .args([
            "table",
            "thesis-4.1",
            "--size",
            "32x32",
            "--effects",
            "direct,ao",
        ])
        .args(["--frames", "1000000", "--warmup", "0", "--out"])
        .arg(out)
        .stderr(Stdio::piped())
        .stdout(Stdio::null())
        .spawn()
        .unwrap();
    let stderr = child.stderr.take().unwrap();
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        for line in BufReader::new(stderr).lines().map_while(Result::ok) {
            if tx.send(line).is_err() {
                break;
            }
        }
    });
    (child, rx)
}

/// Wait until the table is rendering (the device line is out, then a moment for frames).
fn wait_until_rendering(rx: &mpsc::Receiver<String>, seen: &mut Vec<String>) {
    let deadline = Instant::now() + Duration::from_secs(120);
    while Instant::now() < deadline {
        if let Ok(line) = rx.recv_timeout(Duration::from_millis(100)) {
            let started = line.starts_with("device:");
            seen.push(line);
            if started {
                std::thread::sleep(Duration::from_secs(2));
                return;
            }
        }
    }
    panic!("the table never started:\n{}", seen.join("\n"));
}

fn signal(child: &Child, name: &str) {
    let status = Command::new("kill")
        .args([format!("-{name}"), child.id().to_string()])
        .status()
        .unwrap();
    assert!(status.success(), "kill -{name}");
}

fn wait(child: &mut Child) -> std::process::ExitStatus {
    let deadline = Instant::now() + Duration::from_secs(60);
    loop {
        if let Some(status) = child.try_wait().unwrap() {
            return status;
        }
        if Instant::now() > deadline {
            child.kill().ok();
            panic!("ssgi did not stop within 60 s of the signal");
        }
        std::thread::sleep(Duration::from_millis(50));
    }
}

/// The directory holds the previous report and nothing else (no temporary file, no report
/// of the unfinished run).
fn assert_only_previous(dir: &Path) {
    assert_eq!(
        std::fs::read_to_string(dir.join("report.json")).unwrap(),
        PREVIOUS
    );
    let names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(names, vec!["report.json".to_string()], "{names:?}");
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn ctrl_c_stops_a_table_cleanly_and_keeps_the_previous_report() {
    let dir = out_dir("sigint");
    let (mut child, rx) = start_table(&dir);
    let mut seen = Vec::new();
    wait_until_rendering(&rx, &mut seen);
    signal(&child, "INT");
    let status = wait(&mut child);
    seen.extend(rx.try_iter());
    let stderr = seen.join("\n");
    assert_eq!(status.code(), Some(130), "{stderr}");
    assert!(stderr.contains("interrupted: stopped cleanly"), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert_only_previous(&dir);
}

#[test]
fn sigkill_mid_table_leaves_the_previous_report_whole() {
    let dir = out_dir("sigkill");
    let (mut child, rx) = start_table(&dir);
    wait_until_rendering(&rx, &mut Vec::new());
    signal(&child, "KILL");
    let status = wait(&mut child);
    assert_eq!(status.code(), None, "killed by a signal");
    assert_only_previous(&dir);
}
