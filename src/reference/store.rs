//! On-disk cache of references, keyed by everything they depend on: the mesh (positions,
//! normals, texture coordinates, indices, materials and texture pixels), camera, light, size
//! and settings. A cached reference keeps both halves' sums, so a later run that needs a
//! smaller standard error adds samples to it instead of starting again.

use super::estimate::Estimate;
use super::trace::{Reference, Settings};
use crate::error::{Error, Result};
use crate::files::write_atomic;
use crate::scene::{Camera, Scene};
use std::path::{Path, PathBuf};

/// Bump when the estimators or the file layout change: old entries then miss. v2: the
/// shading normal's side is decided per triangle (`Surface::facing`).
const FORMAT: &[u8] = b"ssgi-reference-v2";

/// FNV-1a, 64 bit: stable across Rust releases and platforms (std's hasher is not), and
/// collisions are irrelevant at the scale of a cache directory.
struct Fnv(u64);

impl Fnv {
    fn new() -> Self {
        Fnv(0xcbf2_9ce4_8422_2325)
    }
    fn bytes(&mut self, b: &[u8]) {
        for &x in b {
            self.0 = (self.0 ^ x as u64).wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
    fn f32s(&mut self, v: &[f32]) {
        for x in v {
            self.bytes(&x.to_le_bytes());
        }
    }
}

/// The cache key of a reference (hex).
pub fn key(scene: &Scene, camera: &Camera, width: u32, height: u32, settings: &Settings) -> String {
    let mut h = Fnv::new();
    h.bytes(FORMAT);
    let mesh = &scene.mesh;
    h.bytes(&mesh.vertex_bytes());
    h.bytes(&mesh.index_bytes());
    for r in &mesh.ranges {
        h.bytes(
            &[r.material as u32, r.first_index, r.index_count]
                .map(u32::to_le_bytes)
                .concat(),
        );
    }
    for m in &mesh.materials {
        h.f32s(&m.diffuse);
        if let Some(t) = &m.diffuse_texture {
            h.bytes(&[t.width, t.height].map(u32::to_le_bytes).concat());
            h.bytes(&t.rgba8);
        }
    }
    let c = camera;
    h.f32s(&[c.position.to_array(), c.target.to_array(), c.up.to_array()].concat());
    h.f32s(&[c.vfov_deg, c.near, c.far]);
    let l = &scene.light;
    h.f32s(
        &[
            l.position.to_array(),
            l.direction.to_array(),
            l.intensity.to_array(),
        ]
        .concat(),
    );
    h.f32s(&[l.inner_deg, l.outer_deg, l.near, l.far]);
    h.bytes(&[width, height].map(u32::to_le_bytes).concat());
    h.f32s(&[
        settings.ao.radius,
        settings.ao.attenuation[0],
        settings.ao.attenuation[1],
    ]);
    h.f32s(&[settings.light_radius]);
    h.bytes(&settings.seed.to_le_bytes());
    format!("{:016x}", h.0)
}

/// The cache directory: `$SSGI_CACHE`, else `$XDG_CACHE_HOME/ssgi`, else `~/.cache/ssgi`, else
/// the system's temporary directory; references live in its `reference/` folder.
pub fn default_dir() -> PathBuf {
    let base = std::env::var_os("SSGI_CACHE")
        .map(PathBuf::from)
        .or_else(|| std::env::var_os("XDG_CACHE_HOME").map(|d| PathBuf::from(d).join("ssgi")))
        .or_else(|| std::env::var_os("HOME").map(|d| PathBuf::from(d).join(".cache/ssgi")))
        .unwrap_or_else(|| std::env::temp_dir().join("ssgi"));
    base.join("reference")
}

fn file(dir: &Path, key: &str) -> PathBuf {
    dir.join(format!("{key}.bin"))
}

fn estimates(r: &mut Reference) -> [&mut Estimate; 4] {
    [&mut r.ao, &mut r.direct, &mut r.shadow, &mut r.indirect]
}

/// Write the sums of `r` under `key`.
pub fn save(dir: &Path, key: &str, r: &mut Reference) -> Result<()> {
    let mut out = Vec::new();
    out.extend_from_slice(FORMAT);
    out.extend_from_slice(&r.width.to_le_bytes());
    out.extend_from_slice(&r.height.to_le_bytes());
    out.extend_from_slice(&r.rays.to_le_bytes());
    out.extend_from_slice(&r.seconds.to_le_bytes());
    for e in estimates(r) {
        out.extend_from_slice(&(e.channels as u32).to_le_bytes());
        out.extend_from_slice(&e.per_half.to_le_bytes());
        for half in &e.sums {
            for v in half {
                out.extend_from_slice(&v.to_le_bytes());
            }
        }
    }
    write_atomic(&file(dir, key), &out)
}

/// Fill `r` (fresh, same size) from the cache; false when there is no entry. A damaged or
/// mismatched entry is an error naming the file (delete it, or run with --no-cache).
pub fn load(dir: &Path, key: &str, r: &mut Reference) -> Result<bool> {
    let path = file(dir, key);
    let bytes = match std::fs::read(&path) {
        Ok(b) => b,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(false),
        Err(source) => return Err(Error::Io { path, source }),
    };
    let bad = |what: &str| {
        Error::Config(format!(
            "{}: damaged reference cache entry ({what}); delete it or use --no-cache",
            path.display()
        ))
    };
    let mut at = 0usize;
    let mut take = |n: usize| -> Result<&[u8]> {
        let s = bytes.get(at..at + n).ok_or_else(|| bad("too short"))?;
        at += n;
        Ok(s)
    };
    if take(FORMAT.len())? != FORMAT {
        return Err(bad("unknown format"));
    }
    let u32_ = |b: &[u8]| u32::from_le_bytes(b.try_into().unwrap_or_default());
    let (w, h) = (u32_(take(4)?), u32_(take(4)?));
    if (w, h) != (r.width, r.height) {
        return Err(bad("size"));
    }
    let rays = u64::from_le_bytes(take(8)?.try_into().unwrap_or_default());
    let seconds = f64::from_le_bytes(take(8)?.try_into().unwrap_or_default());
    let pixels = r.primary.len();
    let mut loaded = Vec::new();
    for e in estimates(r) {
        let channels = u32_(take(4)?) as usize;
        let per_half = u32_(take(4)?);
        if channels != e.channels {
            return Err(bad("channels"));
        }
        let mut sums = [Vec::new(), Vec::new()];
        for half in &mut sums {
            let raw = take(8 * channels * pixels)?;
            *half = raw
                .chunks_exact(8)
                .map(|c| f64::from_le_bytes(c.try_into().unwrap_or_default()))
                .collect();
            if half.iter().any(|v| !v.is_finite()) {
                return Err(bad("non-finite sum"));
            }
        }
        loaded.push((per_half, sums));
    }
    if at != bytes.len() {
        return Err(bad("trailing bytes"));
    }
    for (e, (per_half, sums)) in estimates(r).into_iter().zip(loaded) {
        e.per_half = per_half;
        e.sums = sums;
    }
    r.rays = rays;
    r.seconds = seconds;
    Ok(true)
}
