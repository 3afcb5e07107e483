//! Errors for everything the scene module reads: OBJ/MTL files, scene specs, camera paths.
//!
//! Line-level errors print like a compiler: `path:line: message`, so a user can jump straight
//! to the offending line of a broken file.

use std::path::PathBuf;

#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    /// A file could not be opened or read.
    #[error("cannot read {}: {source}", .path.display())]
    Io {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },

    /// A number on a `v`/`vn`/`vt` line is NaN or infinite (or overflows f32).
    #[error("{}:{line}: non-finite coordinate in {kind} '{text}'", .path.display())]
    NonFinite {
        path: PathBuf,
        line: usize,
        kind: &'static str,
        text: String,
    },

    /// A number on a `v`/`vn`/`vt` line does not parse, or the line has too few numbers.
    #[error("{}:{line}: bad number in {kind} '{text}': {reason}", .path.display())]
    BadNumber {
        path: PathBuf,
        line: usize,
        kind: &'static str,
        text: String,
        reason: String,
    },

    /// A coordinate so large (|x| > 1e7) that f32 depth and positions would be meaningless.
    #[error(
        "{}:{line}: huge coordinate in {kind} '{text}' (|x| > 1e7; rescale the model)",
        .path.display()
    )]
    HugeCoordinate {
        path: PathBuf,
        line: usize,
        kind: &'static str,
        text: String,
    },

    /// A face refers to a vertex/normal/texcoord that does not exist (positive or relative).
    #[error(
        "{}:{line}: {kind} index {index} out of range ({count} defined{when}) in '{text}'",
        .path.display(),
        when = if *.index < 0 { " so far" } else { " in the file" }
    )]
    IndexOutOfRange {
        path: PathBuf,
        line: usize,
        kind: &'static str,
        index: i64,
        count: usize,
        text: String,
    },

    /// A face with fewer than three vertices.
    #[error("{}:{line}: face with {count} vertices (need at least 3) '{text}'", .path.display())]
    TooFewVertices {
        path: PathBuf,
        line: usize,
        count: usize,
        text: String,
    },

    /// Any other malformed line (bad face token, `usemtl` without a name, ...).
    #[error("{}:{line}: {message}", .path.display())]
    Syntax {
        path: PathBuf,
        line: usize,
        message: String,
    },

    /// The OBJ parsed but has no (non-degenerate) triangles to draw.
    #[error("{}: no faces to draw ({reason})", .path.display())]
    EmptyMesh { path: PathBuf, reason: String },

    /// tobj rejected a file that passed validation (should not happen; kept so it never panics).
    #[error("{}: OBJ loader failed: {message}", .path.display())]
    Obj { path: PathBuf, message: String },

    /// The scene spec names no built-in scene, file or asset.
    #[error("unknown scene '{spec}': {details}")]
    UnknownScene { spec: String, details: String },
    /// A model too small to render (`validate::MIN_SCENE_RADIUS`).
    #[error("{spec}: {message}")]
    TooSmall { spec: String, message: String },

    /// An asset folder holds several OBJ files, so the asset name is ambiguous.
    #[error(
        "asset '{name}' in {} holds several .obj files ({}); pass one of them as a path",
        .dir.display(),
        .candidates.join(", ")
    )]
    AmbiguousAsset {
        name: String,
        dir: PathBuf,
        candidates: Vec<String>,
    },

    /// A scene file (TOML) is malformed: its line (when the key is written) and dotted key.
    #[error(
        "{}{}: {key}: {message}",
        .path.display(),
        .line.map(|l| format!(":{l}")).unwrap_or_default()
    )]
    SceneFile {
        path: PathBuf,
        line: Option<usize>,
        key: String,
        message: String,
    },

    /// A camera path spec or keyframe file is invalid: its line when known (a TOML file's
    /// key), and why (naming the keyframe and key).
    #[error(
        "camera path {}{}: {message}",
        .path.display(),
        .line.map(|l| format!(":{l}")).unwrap_or_default()
    )]
    CameraPath {
        path: PathBuf,
        line: Option<usize>,
        message: String,
    },

    /// A light path file (`--light-path`) is invalid, as [`SceneError::CameraPath`].
    #[error(
        "light path {}{}: {message}",
        .path.display(),
        .line.map(|l| format!(":{l}")).unwrap_or_default()
    )]
    LightPath {
        path: PathBuf,
        line: Option<usize>,
        message: String,
    },
}
