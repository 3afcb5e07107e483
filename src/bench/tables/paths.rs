//! Camera paths of the tables: keyframe files in the repository's `paths/`, compiled into the
//! binary so that a prebuilt binary needs no other file.

use crate::error::Result;
use crate::scene::{CameraPath, Keyframe, SceneError};
use std::path::PathBuf;

/// A keyframe file of `paths/`: its repository path and contents.
#[derive(Clone, Copy, Debug)]
pub struct EmbeddedPath {
    pub file: &'static str,
    pub text: &'static str,
}

/// Table 4.1's path: around the model inside the box room, from the open side.
pub const BOX: EmbeddedPath = EmbeddedPath {
    file: "paths/box.json",
    text: include_str!("../../../paths/box.json"),
};
pub const SPONZA: EmbeddedPath = EmbeddedPath {
    file: "paths/sponza.json",
    text: include_str!("../../../paths/sponza.json"),
};
pub const SIBENIK: EmbeddedPath = EmbeddedPath {
    file: "paths/sibenik.json",
    text: include_str!("../../../paths/sibenik.json"),
};
pub const CONFERENCE: EmbeddedPath = EmbeddedPath {
    file: "paths/conference.json",
    text: include_str!("../../../paths/conference.json"),
};

#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct KeyframeFile {
    keyframes: Vec<Keyframe>,
}

impl EmbeddedPath {
    /// The compiled-in keyframes (the test below checks they pass the file loader's checks).
    pub fn parse(&self) -> Result<CameraPath> {
        let parsed: KeyframeFile =
            serde_json::from_str(self.text).map_err(|e| SceneError::CameraPath {
                path: PathBuf::from(self.file),
                line: None,
                message: format!("invalid JSON: {e}"),
            })?;
        Ok(CameraPath::Keyframes(parsed.keyframes))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    /// The compiled-in keyframes are the repository files, and pass the loader's checks.
    #[test]
    fn compiled_paths_match_the_files() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        for p in [BOX, SPONZA, SIBENIK, CONFERENCE] {
            let compiled = p.parse().unwrap();
            let from_file = CameraPath::from_file(&root.join(p.file)).unwrap();
            assert_eq!(compiled, from_file, "{}", p.file);
            let CameraPath::Keyframes(keys) = compiled else {
                panic!("{}: not keyframes", p.file)
            };
            assert!(keys.len() >= 4, "{}: a walkthrough needs turns", p.file);
        }
    }
}
