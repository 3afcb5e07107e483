//! Fuzzing the parsers users feed files to: OBJ, MTL and camera keyframes (JSON / TOML).
//! Seeds are the fixtures, the camera paths and the first lines of every shared model; each
//! case mutates one (truncate, splice, flip bytes, delete a range, insert NaN, huge numbers,
//! bad indices, keywords). Every case must load or fail with an error that names the file,
//! never panic. Deterministic (fixed seed), 10,000 cases per run.

use ssgi::scene::{load_obj, CameraPath};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};

const CASES: usize = 10_000;
/// Bytes kept from the start of each shared model (cut at a line end): the real files'
/// syntax without their size.
const MODEL_PREFIX: usize = 6_000;

/// Tokens spliced in: the numbers and statements parsers get wrong.
const TOKENS: &[&str] = &[
    "nan",
    "-nan",
    "inf",
    "-inf",
    "1e39",
    "-1e39",
    "1e-45",
    "-0",
    "3.4028236e38",
    "99999999999",
    "18446744073709551616",
    "0x10",
    "1.2.3",
    "",
    " ",
    "\t",
    "\n",
    "\r\n",
    "/",
    "//",
    "f 1 2 3\n",
    "f -1 -2 -3\n",
    "f 0 0 0\n",
    "f 1/2/3 4//5 6/7\n",
    "f 1\n",
    "f 4294967295 1 2\n",
    "f -4294967296 1 2\n",
    "v 1 2\n",
    "v nan 0 0\n",
    "vt 0.5\n",
    "vn 0 0 0\n",
    "usemtl\n",
    "usemtl missing\n",
    "mtllib\n",
    "mtllib ../../etc/passwd\n",
    "mtllib m.mtl\n",
    "newmtl\n",
    "Kd -1 2 nan\n",
    "map_Kd nowhere.png\n",
    "\u{feff}",
    "#",
    "\u{0}",
    "é",
    "{",
    "}",
    "[",
    "]",
    "\"",
    "=",
    "time",
    "position",
    "target",
    "[[keyframes]]",
    "\"time\": -1",
    "\"time\": 1e308",
    "[1, 2]",
    "null",
];

/// xorshift64*: deterministic and dependency-free.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

fn mutate(rng: &mut Rng, seed: &[u8]) -> Vec<u8> {
    let mut v = seed.to_vec();
    for _ in 0..1 + rng.below(4) {
        let at = rng.below(v.len() + 1);
        match rng.below(6) {
            0 => v.truncate(at),
            1 => {
                let token = TOKENS[rng.below(TOKENS.len())].as_bytes();
                v.splice(at..at, token.iter().copied());
            }
            2 if !v.is_empty() => {
                let i = rng.below(v.len());
                v[i] ^= 1 << rng.below(8);
            }
            3 => {
                let end = (at + rng.below(64)).min(v.len());
                v.drain(at..end);
            }
            4 => {
                // Splice a chunk of the input somewhere else (lines out of order).
                let from = rng.below(v.len() + 1);
                let end = (from + rng.below(80)).min(v.len());
                let chunk: Vec<u8> = v[from..end].to_vec();
                let at = rng.below(v.len() + 1);
                v.splice(at..at, chunk);
            }
            _ => {
                let i = rng.below(v.len() + 1);
                v.insert(i, b"0123456789 -./\nfv"[rng.below(17)]);
            }
        }
    }
    v
}

fn fixtures(ext: &str) -> Vec<Vec<u8>> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures");
    let mut out: Vec<Vec<u8>> = std::fs::read_dir(dir)
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|e| e == ext))
        .map(|p| std::fs::read(p).unwrap())
        .collect();
    out.sort();
    out
}

/// The start of every shared model's OBJ; the test fails when the assets are missing.
fn model_prefixes() -> Vec<Vec<u8>> {
    let dir = std::env::var_os("SSGI_ASSETS")
        .filter(|v| !v.is_empty())
        .map(PathBuf::from)
        .unwrap_or_else(|| {
            panic!(
                "SSGI_ASSETS is not set: the fuzz seeds include the shared models \
                 (../shared/scenes in this workspace); tools/test sets it"
            )
        });
    let mut out = Vec::new();
    for model in ssgi::scene::list_assets(&dir) {
        let path = ssgi::scene::resolve_model(&model, Some(&dir)).unwrap();
        let bytes = std::fs::read(&path).unwrap();
        let cut = bytes.len().min(MODEL_PREFIX);
        let end = bytes[..cut]
            .iter()
            .rposition(|b| *b == b'\n')
            .map_or(cut, |i| i + 1);
        out.push(bytes[..end].to_vec());
    }
    assert!(out.len() >= 5, "only {} shared models found", out.len());
    out
}

/// Run `load` on `bytes` written to `path`: no panic; an error names the file.
fn check(path: &Path, bytes: &[u8], load: impl FnOnce(&Path) -> Result<(), String>) {
    std::fs::write(path, bytes).unwrap();
    let result = catch_unwind(AssertUnwindSafe(|| load(path)));
    let shown = String::from_utf8_lossy(&bytes[..bytes.len().min(400)]).into_owned();
    match result {
        Err(_) => panic!("{} panicked on input:\n{shown}", path.display()),
        Ok(Err(e)) => {
            let name = path.file_name().unwrap().to_string_lossy();
            assert!(
                e.contains(&*name),
                "error without the file name: {e}\ninput:\n{shown}"
            );
        }
        Ok(Ok(())) => {}
    }
}

#[test]
fn mutated_obj_mtl_and_keyframe_files_never_panic() {
    let dir = std::env::temp_dir().join(format!("ssgi-fuzz-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut objs = fixtures("obj");
    objs.extend(model_prefixes());
    let mtls = fixtures("mtl");
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let keyframes: Vec<(Vec<u8>, &str)> = std::fs::read_dir(root.join("paths"))
        .unwrap()
        .flatten()
        .map(|e| (std::fs::read(e.path()).unwrap(), "json"))
        .chain([(
            b"[[keyframes]]\ntime = 0.0\nposition = [0, 1, 3]\ntarget = [0, 1, 0]\n\n\
              [[keyframes]]\ntime = 1.0\nposition = [1, 1, 3]\ntarget = [0, 1, 0]\n"
                .to_vec(),
            "toml",
        )])
        .collect();
    let mut rng = Rng(0x5eed_f022_ab1e_0001);
    let (mut loaded, mut refused) = (0, 0);
    let mut count = |ok: bool| if ok { loaded += 1 } else { refused += 1 };
    for case in 0..CASES {
        match case % 10 {
            // 60 % OBJ, with a valid MTL beside it for `mtllib m.mtl`.
            0..=5 => {
                let seed = &objs[rng.below(objs.len())];
                std::fs::write(dir.join("m.mtl"), &mtls[0]).unwrap();
                let path = dir.join(format!("case{case}.obj"));
                let mut ok = false;
                check(&path, &mutate(&mut rng, seed), |p| {
                    load_obj(p).map(|_| ok = true).map_err(|e| e.to_string())
                });
                count(ok);
            }
            // 20 % MTL: a mutated library under a valid OBJ (MTL problems become warnings).
            6 | 7 => {
                let seed = &mtls[rng.below(mtls.len())];
                let mtl = mutate(&mut rng, seed);
                std::fs::write(dir.join("m.mtl"), mtl).unwrap();
                let obj = b"mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n";
                let path = dir.join(format!("case{case}.obj"));
                let mut ok = false;
                check(&path, obj, |p| {
                    load_obj(p).map(|_| ok = true).map_err(|e| e.to_string())
                });
                assert!(ok, "a bad MTL must not make a valid OBJ fail");
                count(ok);
            }
            // 20 % camera keyframes.
            _ => {
                let (seed, ext) = &keyframes[rng.below(keyframes.len())];
                let path = dir.join(format!("case{case}.{ext}"));
                let mut ok = false;
                check(&path, &mutate(&mut rng, seed), |p| {
                    CameraPath::from_file(p)
                        .map(|_| ok = true)
                        .map_err(|e| e.to_string())
                });
                count(ok);
            }
        }
        // Keep the directory small.
        let _ = std::fs::remove_file(dir.join(format!("case{case}.obj")));
    }
    std::fs::remove_dir_all(&dir).unwrap();
    println!("{CASES} cases: {loaded} loaded, {refused} refused with a named error");
    // Both outcomes occur: the mutations reach past the parsers' first checks.
    assert!(
        loaded > CASES / 20 && refused > CASES / 20,
        "{loaded} / {refused}"
    );
}
