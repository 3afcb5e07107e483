//! OBJ + MTL loading: validation pass, tobj parse, materials/textures, normals, degenerate
//! triangle removal, merge of all tobj models into one [`Mesh`].

use super::builder::MeshBuilder;
use super::error::SceneError;
use super::input::read_regular;
use super::mesh::{Material, Mesh, Vertex};
use super::normals::area_weighted_normals;
use super::texture::{non_utf8_map_kd, resolve_texture_path, TextureCache};
use super::validate::{validate_mtl, validate_obj, ObjSummary};
use glam::Vec3;
use std::borrow::Cow;
use std::cell::RefCell;
use std::collections::HashMap;
use std::io::Cursor;
use std::path::{Path, PathBuf};

/// A sliver's largest accepted thinness: a triangle whose height over its longest edge is
/// below `SLIVER_RELATIVE_HEIGHT × longest edge` is dropped. `f32::EPSILON` is the relative
/// precision of each edge vector's own components, so a thinner triangle's plane (and normal)
/// is rounding noise. The rule looks at the triangle alone: tiny but well-shaped triangles of a
/// large model are kept whatever their size against the model.
pub const SLIVER_RELATIVE_HEIGHT: f64 = f32::EPSILON as f64;

/// Loads an OBJ file (and its MTL files and diffuse textures) into one mesh.
///
/// Errors name the file and, for content errors, the line. Problems that still leave a
/// drawable mesh (missing MTL or texture, unknown material, non-UTF-8 bytes) become warnings
/// in `mesh.stats.warnings`.
pub fn load_obj(path: &Path) -> Result<Mesh, SceneError> {
    let bytes = read_regular(path, None).map_err(|source| SceneError::Io {
        path: path.to_owned(),
        source,
    })?;
    let mut warnings = Vec::new();
    let text = match String::from_utf8(bytes) {
        Ok(s) => s,
        Err(e) => {
            warnings.push(format!(
                "{}: not valid UTF-8 (byte {}); invalid bytes were replaced",
                path.display(),
                e.utf8_error().valid_up_to()
            ));
            String::from_utf8_lossy(e.as_bytes()).into_owned()
        }
    };
    // A byte-order mark would hide the first keyword from tobj and shift every index.
    let text = text.strip_prefix('\u{feff}').unwrap_or(&text);

    let summary = validate_obj(path, text)?;
    if summary.faces == 0 {
        return Err(SceneError::EmptyMesh {
            path: path.to_owned(),
            reason: "the file has no 'f' lines".into(),
        });
    }
    let text = blank_line_elements(text, &summary, path, &mut warnings);

    let parsed = parse_with_tobj(path, &text, &mut warnings)?;
    let mut builder = MeshBuilder::new();
    let materials = MaterialTable::new(&parsed, &summary, &mut warnings);
    add_geometry(path, &parsed.models, materials, &mut builder)?;

    let stats = builder.stats_mut();
    stats.faces = summary.faces;
    stats.warnings.splice(0..0, warnings);
    let mesh = builder.build();
    if mesh.indices.is_empty() {
        return Err(SceneError::EmptyMesh {
            path: path.to_owned(),
            reason: format!(
                "all {} triangles are degenerate (zero area)",
                mesh.stats.triangles
            ),
        });
    }
    Ok(mesh)
}

/// tobj turns `l a b c` into a triangle; lines are not surfaces, so blank them (keeping line
/// numbers intact) before tobj sees the text.
fn blank_line_elements<'a>(
    text: &'a str,
    summary: &ObjSummary,
    path: &Path,
    warnings: &mut Vec<String>,
) -> Cow<'a, str> {
    if summary.line_elements.is_empty() {
        return Cow::Borrowed(text);
    }
    warnings.push(format!(
        "{}: ignored {} line element(s) ('l'), first on line {}",
        path.display(),
        summary.line_elements.len(),
        summary.line_elements[0]
    ));
    let mut out = String::with_capacity(text.len());
    let mut next = summary.line_elements.iter().peekable();
    for (i, line) in text.lines().enumerate() {
        if next.peek() == Some(&&(i + 1)) {
            next.next();
        } else {
            out.push_str(line);
        }
        out.push('\n');
    }
    Cow::Owned(out)
}

struct Parsed {
    models: Vec<tobj::Model>,
    materials: Vec<tobj::Material>,
    /// Directory of the MTL file each material came from (textures resolve against it).
    material_dirs: Vec<PathBuf>,
    /// `map_Kd` names that are not UTF-8, by the text tobj gives (`non_utf8_map_kd`).
    raw_texture_names: HashMap<String, std::ffi::OsString>,
}

fn parse_with_tobj(
    path: &Path,
    text: &str,
    warnings: &mut Vec<String>,
) -> Result<Parsed, SceneError> {
    let obj_dir = path.parent().unwrap_or(Path::new("")).to_owned();
    // tobj calls the loader once per `mtllib`, appending materials in call order; the log
    // maps each material back to its file. A broken MTL becomes a warning and no materials.
    let mtl_log: RefCell<Vec<(PathBuf, usize)>> = RefCell::default();
    let mtl_warnings: RefCell<Vec<String>> = RefCell::default();
    let raw_names: RefCell<HashMap<String, std::ffi::OsString>> = RefCell::default();
    let load_mtl = |name: &Path| {
        let full = obj_dir.join(name);
        match read_mtl(&full) {
            Ok((loaded, raw)) => {
                mtl_log.borrow_mut().push((full, loaded.0.len()));
                raw_names.borrow_mut().extend(raw);
                Ok(loaded)
            }
            Err(why) => {
                mtl_warnings.borrow_mut().push(format!(
                    "material library {}: {why}; using the default material",
                    full.display()
                ));
                Ok(Default::default())
            }
        }
    };
    let (models, materials) = tobj::load_obj_buf(
        &mut Cursor::new(text.as_bytes()),
        &tobj::GPU_LOAD_OPTIONS,
        load_mtl,
    )
    .map_err(|e| SceneError::Obj {
        path: path.to_owned(),
        message: e.to_string(),
    })?;
    warnings.extend(mtl_warnings.into_inner());
    // The loader never returns Err, so an Err here can only mean "no materials".
    let materials = materials.unwrap_or_default();
    let mut material_dirs = Vec::with_capacity(materials.len());
    for (mtl_path, count) in mtl_log.into_inner() {
        let dir = mtl_path.parent().unwrap_or(Path::new("")).to_owned();
        material_dirs.extend(std::iter::repeat_n(dir, count));
    }
    material_dirs.resize(materials.len(), obj_dir);
    Ok(Parsed {
        models,
        materials,
        material_dirs,
        raw_texture_names: raw_names.into_inner(),
    })
}

/// Largest MTL file read: the papers' models' are at most a few tens of KiB, so a larger
/// one is not a material library (docs/scenes.md).
pub const MAX_MTL_BYTES: u64 = 16 << 20;

/// Reads and parses one MTL file, with its `map_Kd` names that are not UTF-8; the error says
/// why it is unusable.
fn read_mtl(path: &Path) -> Result<(MtlLoaded, HashMap<String, std::ffi::OsString>), String> {
    let bytes =
        read_regular(path, Some(MAX_MTL_BYTES)).map_err(|e| format!("cannot read it ({e})"))?;
    let text = String::from_utf8_lossy(&bytes);
    let text = text.strip_prefix('\u{feff}').unwrap_or(&text);
    validate_mtl(path, text).map_err(|e| e.to_string())?;
    let loaded = tobj::load_mtl_buf(&mut Cursor::new(text.as_bytes()))
        .map_err(|e| format!("cannot parse it ({e})"))?;
    Ok((loaded, non_utf8_map_kd(&bytes)))
}

/// What tobj's MTL parser returns on success: materials and tobj's name → index map.
type MtlLoaded = <tobj::MTLLoadResult as IntoIterator>::Item;

/// Converts tobj materials to ours on first use, so unused materials cost no texture decode.
struct MaterialTable<'a> {
    parsed: &'a Parsed,
    textures: TextureCache,
    /// tobj material index -> builder material index.
    converted: HashMap<usize, usize>,
    default: Option<usize>,
    warnings: &'a mut Vec<String>,
}

impl<'a> MaterialTable<'a> {
    fn new(parsed: &'a Parsed, summary: &ObjSummary, warnings: &'a mut Vec<String>) -> Self {
        for name in &summary.used_materials {
            if !parsed.materials.iter().any(|m| &m.name == name) {
                warnings.push(format!(
                    "usemtl '{name}': no such material in the MTL files; using the default material"
                ));
            }
        }
        Self {
            parsed,
            textures: TextureCache::new(),
            converted: HashMap::new(),
            default: None,
            warnings,
        }
    }

    fn get(&mut self, id: Option<usize>, builder: &mut MeshBuilder) -> usize {
        let Some(id) = id.filter(|&i| i < self.parsed.materials.len()) else {
            return *self
                .default
                .get_or_insert_with(|| builder.add_material(Material::default_material()));
        };
        if let Some(&m) = self.converted.get(&id) {
            return m;
        }
        let material = self.convert(id);
        let m = builder.add_material(material);
        self.converted.insert(id, m);
        m
    }

    fn convert(&mut self, id: usize) -> Material {
        let src = &self.parsed.materials[id];
        let mut diffuse = Material::DEFAULT_DIFFUSE;
        if let Some(kd) = src.diffuse {
            if kd.iter().all(|c| c.is_finite()) {
                // Albedo above 1 would create energy; below 0 is meaningless.
                diffuse = kd.map(|c| c.clamp(0.0, 1.0));
                if diffuse != kd {
                    self.warnings.push(format!(
                        "material '{}': Kd {kd:?} clamped to [0, 1]",
                        src.name
                    ));
                }
            } else {
                self.warnings.push(format!(
                    "material '{}': non-finite Kd {kd:?}; using {diffuse:?}",
                    src.name
                ));
            }
        }
        let diffuse_texture = src.diffuse_texture.as_deref().and_then(|name| {
            let dir = &self.parsed.material_dirs[id];
            let path = match self.parsed.raw_texture_names.get(name) {
                Some(raw) => resolve_texture_path(dir, raw.as_encoded_bytes()),
                None => resolve_texture_path(dir, name),
            };
            match self.textures.load(&path) {
                Ok(tex) => Some(tex),
                Err(e) => {
                    self.warnings.push(format!(
                        "material '{}': diffuse texture {} unusable ({e}); using its Kd colour",
                        src.name,
                        path.display()
                    ));
                    None
                }
            }
        });
        Material {
            name: src.name.clone(),
            diffuse,
            diffuse_texture,
        }
    }
}

fn add_geometry(
    path: &Path,
    models: &[tobj::Model],
    mut materials: MaterialTable,
    builder: &mut MeshBuilder,
) -> Result<(), SceneError> {
    for model in models {
        let m = &model.mesh;
        let positions: Vec<Vec3> = m
            .positions
            .chunks_exact(3)
            .map(|p| Vec3::new(p[0], p[1], p[2]))
            .collect();
        let n = positions.len();
        let mut triangles = Vec::with_capacity(m.indices.len() / 3);
        let (mut zero_area, mut slivers) = (0, 0);
        for t in m.indices.chunks_exact(3) {
            let tri = [t[0], t[1], t[2]];
            if tri.iter().any(|&i| i as usize >= n) {
                return Err(SceneError::Obj {
                    path: path.to_owned(),
                    message: format!("object '{}': index out of range after parsing", model.name),
                });
            }
            let [a, b, c] = tri.map(|i| positions[i as usize]);
            match degeneracy(a, b, c) {
                None => triangles.push(tri),
                Some(Degeneracy::ZeroArea) => zero_area += 1,
                Some(Degeneracy::Sliver) => slivers += 1,
            }
        }
        let stats = builder.stats_mut();
        stats.triangles += m.indices.len() / 3;
        stats.dropped_zero_area += zero_area;
        stats.dropped_slivers += slivers;
        if triangles.is_empty() {
            continue;
        }

        let normals = vertex_normals(model, &positions, &triangles, materials.warnings);
        let uvs = texcoords(model, n, materials.warnings);
        let material = materials.get(m.material_id, builder);
        let base = builder.vertex_count() as u32;
        for i in 0..n {
            builder.push_vertex(Vertex::new(positions[i], normals[i], uvs(i)));
        }
        for tri in triangles {
            builder.push_triangle(material, tri.map(|i| i + base));
        }
    }
    Ok(())
}

/// File normals, normalised; computed area-weighted normals where the file has none, only
/// some, or zero-length ones.
fn vertex_normals(
    model: &tobj::Model,
    positions: &[Vec3],
    triangles: &[[u32; 3]],
    warnings: &mut Vec<String>,
) -> Vec<Vec3> {
    let file = &model.mesh.normals;
    if file.len() != positions.len() * 3 {
        if !file.is_empty() {
            warnings.push(format!(
                "object '{}': only some face corners have normals; computing all of them",
                model.name
            ));
        }
        return area_weighted_normals(positions, triangles);
    }
    let normalized: Vec<Option<Vec3>> = file
        .chunks_exact(3)
        .map(|n| Vec3::new(n[0], n[1], n[2]).try_normalize())
        .collect();
    if normalized.iter().all(Option::is_some) {
        return normalized.into_iter().flatten().collect();
    }
    let computed = area_weighted_normals(positions, triangles);
    normalized
        .into_iter()
        .zip(computed)
        .map(|(n, c)| n.unwrap_or(c))
        .collect()
}

/// UV lookup per vertex; `v` is flipped so (0, 0) is the image's first (top) row.
fn texcoords<'m>(
    model: &'m tobj::Model,
    n: usize,
    warnings: &mut Vec<String>,
) -> impl Fn(usize) -> [f32; 2] + 'm {
    let tc = &model.mesh.texcoords;
    let usable = tc.len() == n * 2;
    if !usable && !tc.is_empty() {
        warnings.push(format!(
            "object '{}': only some face corners have texture coordinates; using (0, 0)",
            model.name
        ));
    }
    move |i| {
        if usable {
            [tc[2 * i], 1.0 - tc[2 * i + 1]]
        } else {
            [0.0, 0.0]
        }
    }
}

/// Why a triangle is not drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Degeneracy {
    /// Zero area: repeated or collinear corners (exact: see [`degeneracy`]).
    ZeroArea,
    /// Nonzero area but thinner than [`SLIVER_RELATIVE_HEIGHT`] of its own longest edge.
    Sliver,
}

/// Is this triangle degenerate, and how? In f64: the differences of f32 corners are exact
/// there and the products of the cross product nearly so, so "zero area" means collinear
/// corners, not an underflow; large coordinates neither overflow nor lose a small area.
pub fn degeneracy(a: Vec3, b: Vec3, c: Vec3) -> Option<Degeneracy> {
    let (a, b, c) = (a.as_dvec3(), b.as_dvec3(), c.as_dvec3());
    let twice_area = (b - a).cross(c - a).length();
    if twice_area == 0.0 {
        return Some(Degeneracy::ZeroArea);
    }
    let longest_squared = (b - a)
        .length_squared()
        .max((c - b).length_squared())
        .max((a - c).length_squared());
    // height = 2A / L; dropped when height < k L, i.e. 2A < k L².
    (twice_area < SLIVER_RELATIVE_HEIGHT * longest_squared).then_some(Degeneracy::Sliver)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn degeneracy_depends_on_the_triangle_alone() {
        for scale in [1e-20f32, 1e-3, 1.0, 1e4, 1e20] {
            let (a, b) = (Vec3::ZERO, Vec3::X * scale);
            let d = |c: Vec3| degeneracy(a, b, c * scale);
            assert_eq!(d(Vec3::X * 2.0), Some(Degeneracy::ZeroArea), "{scale}");
            assert_eq!(d(Vec3::X), Some(Degeneracy::ZeroArea), "{scale}");
            assert_eq!(
                d(Vec3::new(0.5, 1e-8, 0.0)),
                Some(Degeneracy::Sliver),
                "{scale}"
            );
            assert_eq!(d(Vec3::new(0.5, 1e-6, 0.0)), None, "{scale}");
            assert_eq!(d(Vec3::Y * 1e-4), None, "{scale}");
        }
    }
}
