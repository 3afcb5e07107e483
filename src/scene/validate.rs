//! A fast line-based pass over OBJ text that runs before tobj, because tobj reports errors
//! without a line number and accepts NaN/inf. It checks exactly what tobj would trip over (so
//! tobj never fails after this pass) plus what would poison rendering: non-finite or absurdly
//! large numbers and out-of-range indices.

use super::error::SceneError;
use std::collections::BTreeSet;
use std::path::Path;

/// Coordinates beyond this magnitude are rejected: f32 has ~7 significant digits, so beyond
/// 1e7 representable positions are a whole unit apart and depth/position buffers (and every
/// relative epsilon downstream) are meaningless.
pub const HUGE_COORDINATE: f32 = 1e7;

/// The smallest bounding radius of a scene, in metres. Below it the ray-triangle tests of the
/// BVH (obvhs), which the automatic framing and the CPU ground truth use, lose hits (their
/// tolerances do not scale with the scene): the bunny's automatic view is the same, relative
/// to its size, from scale 1 down to 1e-3 (a radius of 1e-4 m) and another one from 1e-4 on;
/// at 1e-11 the image was black. 1e-3 m keeps ten times that margin.
pub const MIN_SCENE_RADIUS: f32 = 1e-3;

/// Why a scene of bounding radius `radius` is too small to render, if it is.
pub fn scene_size_problem(radius: f32) -> Option<String> {
    use std::cmp::Ordering::{Equal, Greater};
    // NaN (no ordering) is too small as well.
    let small = !matches!(radius.partial_cmp(&MIN_SCENE_RADIUS), Some(Greater | Equal));
    small.then(|| {
        format!(
            "the scene's bounding radius {radius:e} m is below {MIN_SCENE_RADIUS:e} m, under \
             which ray tests lose hits (the automatic view changes, the ground truth misses \
             surfaces); scale it up (a scene file's mesh scale)"
        )
    })
}

/// What the validation pass learned about a file.
#[derive(Debug, Default, Clone, PartialEq)]
pub struct ObjSummary {
    /// `f` lines.
    pub faces: usize,
    /// Triangles after fan triangulation (sum of `vertices - 2` over faces).
    pub triangles: usize,
    pub positions: usize,
    pub texcoords: usize,
    pub normals: usize,
    /// Material names used by `usemtl`, sorted.
    pub used_materials: BTreeSet<String>,
    /// 1-based numbers of `l` lines. tobj would turn an `l` with 3+ points into a triangle,
    /// so the loader blanks these lines out.
    pub line_elements: Vec<usize>,
}

#[derive(Clone, Copy)]
enum Attr {
    Position,
    Texcoord,
    Normal,
    Colour,
}

impl Attr {
    fn name(self) -> &'static str {
        match self {
            Attr::Position => "vertex",
            Attr::Texcoord => "texture coordinate",
            Attr::Normal => "normal",
            Attr::Colour => "colour",
        }
    }
}

/// A positive index that pointed past the data defined so far; legal OBJ only if the data
/// appears later, so it is re-checked against the totals at the end.
struct ForwardRef {
    line: usize,
    attr: Attr,
    index: i64,
}

/// Validates OBJ `text`; `path` is only used in messages.
pub fn validate_obj(path: &Path, text: &str) -> Result<ObjSummary, SceneError> {
    let mut s = ObjSummary::default();
    let mut forward = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        let line_no = i + 1;
        let line = raw.trim();
        let mut words = line.split_whitespace();
        let Some(keyword) = words.next() else {
            continue;
        };
        let ctx = LineCtx {
            path,
            line: line_no,
            text: line,
        };
        match keyword {
            "v" => {
                check_position(&ctx, words)?;
                s.positions += 1;
            }
            "vt" => {
                check_numbers(&ctx, words, Attr::Texcoord, 2)?;
                s.texcoords += 1;
            }
            "vn" => {
                check_numbers(&ctx, words, Attr::Normal, 3)?;
                s.normals += 1;
            }
            "f" | "l" => {
                let counts = [s.positions, s.texcoords, s.normals];
                let n = check_face(&ctx, words, counts, &mut forward)?;
                if keyword == "l" {
                    s.line_elements.push(line_no);
                } else if n < 3 {
                    return Err(SceneError::TooFewVertices {
                        path: path.to_owned(),
                        line: line_no,
                        count: n,
                        text: ctx.short_text(),
                    });
                } else {
                    s.faces += 1;
                    s.triangles += n - 2;
                }
            }
            "usemtl" => {
                // tobj takes the name after the first space and fails on an empty one.
                let name = raw.split_once(' ').map(|(_, r)| r.trim()).unwrap_or("");
                if name.is_empty() {
                    return Err(ctx.syntax("usemtl needs a material name after a space"));
                }
                if !s.used_materials.contains(name) {
                    s.used_materials.insert(name.to_owned());
                }
            }
            _ => {}
        }
    }
    for r in forward {
        let count = match r.attr {
            Attr::Position => s.positions,
            Attr::Texcoord => s.texcoords,
            Attr::Normal => s.normals,
            Attr::Colour => 0, // never a face index
        };
        if r.index as u64 > count as u64 {
            let text = text.lines().nth(r.line - 1).unwrap_or("").trim();
            return Err(SceneError::IndexOutOfRange {
                path: path.to_owned(),
                line: r.line,
                kind: r.attr.name(),
                index: r.index,
                count,
                text: shorten(text),
            });
        }
    }
    Ok(s)
}

/// Checks the MTL lines tobj would panic on (it unwraps `Ka/Kd/Ks/Ke` with fewer than three
/// numbers). Everything else tobj reports as an error itself.
pub fn validate_mtl(path: &Path, text: &str) -> Result<(), SceneError> {
    for (i, raw) in text.lines().enumerate() {
        let line = raw.trim();
        let mut words = line.split_whitespace();
        if let Some("Ka" | "Kd" | "Ks" | "Ke") = words.next() {
            let ctx = LineCtx {
                path,
                line: i + 1,
                text: line,
            };
            check_numbers(&ctx, words.take(3), Attr::Colour, 3)?;
        }
    }
    Ok(())
}

struct LineCtx<'a> {
    path: &'a Path,
    line: usize,
    text: &'a str,
}

impl LineCtx<'_> {
    fn short_text(&self) -> String {
        shorten(self.text)
    }

    fn syntax(&self, message: impl Into<String>) -> SceneError {
        SceneError::Syntax {
            path: self.path.to_owned(),
            line: self.line,
            message: format!("{} in '{}'", message.into(), self.short_text()),
        }
    }

    fn bad_number(&self, attr: Attr, reason: impl Into<String>) -> SceneError {
        SceneError::BadNumber {
            path: self.path.to_owned(),
            line: self.line,
            kind: attr.name(),
            text: self.short_text(),
            reason: reason.into(),
        }
    }

    fn non_finite(&self, attr: Attr) -> SceneError {
        SceneError::NonFinite {
            path: self.path.to_owned(),
            line: self.line,
            kind: attr.name(),
            text: self.short_text(),
        }
    }
}

/// Keeps messages readable for absurdly long lines.
fn shorten(text: &str) -> String {
    const MAX: usize = 80;
    match text.char_indices().nth(MAX) {
        Some((cut, _)) => format!("{}...", &text[..cut]),
        None => text.to_owned(),
    }
}

/// Parses every remaining word as a finite f32; requires at least `min` of them.
fn parse_all<'a>(
    ctx: &LineCtx,
    words: impl Iterator<Item = &'a str>,
    attr: Attr,
    min: usize,
) -> Result<Vec<f32>, SceneError> {
    let mut values = Vec::with_capacity(min);
    for w in words {
        let x: f32 = w
            .parse()
            .map_err(|_| ctx.bad_number(attr, format!("'{w}' is not a number")))?;
        if !x.is_finite() {
            return Err(ctx.non_finite(attr));
        }
        values.push(x);
    }
    if values.len() < min {
        return Err(ctx.bad_number(
            attr,
            format!("expected {min} numbers, found {}", values.len()),
        ));
    }
    Ok(values)
}

fn check_numbers<'a>(
    ctx: &LineCtx,
    words: impl Iterator<Item = &'a str>,
    attr: Attr,
    min: usize,
) -> Result<(), SceneError> {
    parse_all(ctx, words, attr, min).map(|_| ())
}

/// `v x y z [w | r g b]`, the forms tobj accepts.
fn check_position<'a>(
    ctx: &LineCtx,
    words: impl Iterator<Item = &'a str>,
) -> Result<(), SceneError> {
    let attr = Attr::Position;
    let v = parse_all(ctx, words, attr, 3)?;
    let w = match v.len() {
        3 | 6 => 1.0,
        4 if v[3] != 0.0 => v[3],
        4 => return Err(ctx.syntax("vertex weight w is 0")),
        n => {
            return Err(ctx.bad_number(
                attr,
                format!("expected 3, 4 (with w) or 6 (with colour) numbers, found {n}"),
            ))
        }
    };
    for x in &v[..3] {
        let x = x / w;
        if !x.is_finite() {
            return Err(ctx.non_finite(attr));
        }
        if x.abs() > HUGE_COORDINATE {
            return Err(SceneError::HugeCoordinate {
                path: ctx.path.to_owned(),
                line: ctx.line,
                kind: attr.name(),
                text: ctx.short_text(),
            });
        }
    }
    Ok(())
}

/// Checks every `v[/vt][/vn]` token of a face; returns the number of corners.
fn check_face<'a>(
    ctx: &LineCtx,
    words: impl Iterator<Item = &'a str>,
    counts: [usize; 3],
    forward: &mut Vec<ForwardRef>,
) -> Result<usize, SceneError> {
    const ATTRS: [Attr; 3] = [Attr::Position, Attr::Texcoord, Attr::Normal];
    let mut n = 0;
    for token in words {
        n += 1;
        let parts: Vec<&str> = token.split('/').collect();
        if parts.len() > 3 {
            return Err(ctx.syntax(format!("face corner '{token}' has more than 3 indices")));
        }
        if parts[0].is_empty() {
            return Err(ctx.syntax(format!("face corner '{token}' has no vertex index")));
        }
        for (k, part) in parts.iter().enumerate() {
            if part.is_empty() {
                continue;
            }
            let index: i64 = part
                .parse()
                .map_err(|_| ctx.syntax(format!("bad face index '{part}' in corner '{token}'")))?;
            let count = counts[k];
            let out_of_range = |index| SceneError::IndexOutOfRange {
                path: ctx.path.to_owned(),
                line: ctx.line,
                kind: ATTRS[k].name(),
                index,
                count,
                text: ctx.short_text(),
            };
            if index == 0 || (index < 0 && index.unsigned_abs() > count as u64) {
                return Err(out_of_range(index));
            }
            if index > 0 && index as u64 > count as u64 {
                forward.push(ForwardRef {
                    line: ctx.line,
                    attr: ATTRS[k],
                    index,
                });
            }
        }
    }
    Ok(n)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(text: &str) -> Result<ObjSummary, SceneError> {
        validate_obj(Path::new("t.obj"), text)
    }

    #[test]
    fn counts_faces_and_triangles() {
        let s = check("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\nf -4 -3 -2\n").unwrap();
        assert_eq!((s.faces, s.triangles, s.positions), (2, 3, 4));
    }

    #[test]
    fn forward_references_are_allowed_if_defined_later() {
        assert!(check("f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n").is_ok());
        let e = check("f 1 2 4\nv 0 0 0\nv 1 0 0\nv 0 1 0\n").unwrap_err();
        assert!(
            matches!(
                e,
                SceneError::IndexOutOfRange {
                    line: 1,
                    index: 4,
                    ..
                }
            ),
            "{e}"
        );
    }

    #[test]
    fn index_zero_and_bad_tokens_are_errors() {
        let e = check("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n").unwrap_err();
        assert!(
            matches!(
                e,
                SceneError::IndexOutOfRange {
                    line: 4,
                    index: 0,
                    ..
                }
            ),
            "{e}"
        );
        let e = check("v 0 0 0\nf 1/2/3/4 1 1\n").unwrap_err();
        assert!(matches!(e, SceneError::Syntax { line: 2, .. }), "{e}");
        let e = check("v 0 0 0\nf 1 1 1.5\n").unwrap_err();
        assert!(matches!(e, SceneError::Syntax { line: 2, .. }), "{e}");
    }

    #[test]
    fn texcoord_and_normal_indices_are_checked() {
        let e = check("v 0 0 0\nvn 0 1 0\nf 1//2 1//1 1//1\n").unwrap_err();
        assert!(
            matches!(
                e,
                SceneError::IndexOutOfRange {
                    kind: "normal",
                    line: 3,
                    ..
                }
            ),
            "{e}"
        );
        let e = check("v 0 0 0\nf 1/-1 1 1\n").unwrap_err();
        assert!(
            matches!(
                e,
                SceneError::IndexOutOfRange {
                    kind: "texture coordinate",
                    ..
                }
            ),
            "{e}"
        );
    }

    #[test]
    fn vertex_forms() {
        assert!(check("v 1 2 3 0.5\nv 1 2 3 1 0 0\n").is_ok());
        assert!(matches!(
            check("v 1 2 3 0\n"),
            Err(SceneError::Syntax { .. })
        ));
        assert!(matches!(
            check("v 1 2\n"),
            Err(SceneError::BadNumber { .. })
        ));
        assert!(matches!(
            check("v 1 2 3 4 5\n"),
            Err(SceneError::BadNumber { .. })
        ));
        // Division by a tiny w makes a finite coordinate huge.
        assert!(matches!(
            check("v 1 2 3 1e-30\n"),
            Err(SceneError::HugeCoordinate { .. } | SceneError::NonFinite { .. })
        ));
        assert!(matches!(
            check("v 1 2 1e39\n"),
            Err(SceneError::NonFinite { .. })
        ));
        assert!(matches!(
            check("vn 0 inf 0\n"),
            Err(SceneError::NonFinite { .. })
        ));
        assert!(matches!(
            check("vt 0.5\n"),
            Err(SceneError::BadNumber { .. })
        ));
    }

    #[test]
    fn crlf_and_usemtl() {
        let s = check("v 0 0 0\r\nusemtl a b\r\nusemtl x\r\n").unwrap();
        assert_eq!(
            s.used_materials.into_iter().collect::<Vec<_>>(),
            ["a b", "x"]
        );
        assert!(matches!(
            check("usemtl\n"),
            Err(SceneError::Syntax { line: 1, .. })
        ));
    }

    #[test]
    fn mtl_colours_need_three_numbers() {
        let p = Path::new("m.mtl");
        assert!(validate_mtl(p, "newmtl a\n\tKd 1 0.5 0\nKs 0 0 0 extra\n").is_ok());
        let e = validate_mtl(p, "newmtl a\nKd 1 0.5\n").unwrap_err();
        assert!(matches!(e, SceneError::BadNumber { line: 2, .. }), "{e}");
        assert!(validate_mtl(p, "Ke 1 x 0\n").is_err());
    }

    #[test]
    fn long_lines_are_shortened() {
        let line = format!("v 0 0 nan {}", "0 ".repeat(200));
        let e = check(&line).unwrap_err().to_string();
        assert!(e.len() < 200, "{e}");
    }
}
