//! CPU-side mesh data in the exact layout the renderer uploads.

use glam::Vec3;
use std::path::PathBuf;
use std::sync::Arc;

/// One vertex as uploaded to the GPU: 32 bytes, tightly packed, no padding.
///
/// `uv` follows the image convention: (0, 0) is the first row of [`TextureImage::rgba8`]
/// (the top of the picture). OBJ `vt` has v pointing up, so the loader stores `1 - v`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Vertex {
    pub position: [f32; 3],
    pub normal: [f32; 3],
    pub uv: [f32; 2],
}

const _: () = assert!(std::mem::size_of::<Vertex>() == 32);
/// Byte offsets of the fields, for the vertex input attribute descriptions.
pub const VERTEX_NORMAL_OFFSET: u32 = 12;
pub const VERTEX_UV_OFFSET: u32 = 24;
const _: () = assert!(std::mem::offset_of!(Vertex, normal) == VERTEX_NORMAL_OFFSET as usize);
const _: () = assert!(std::mem::offset_of!(Vertex, uv) == VERTEX_UV_OFFSET as usize);

impl Vertex {
    pub fn new(position: Vec3, normal: Vec3, uv: [f32; 2]) -> Self {
        Self {
            position: position.to_array(),
            normal: normal.to_array(),
            uv,
        }
    }

    pub fn pos(&self) -> Vec3 {
        Vec3::from_array(self.position)
    }
}

/// A decoded texture, RGBA8 rows top to bottom (`width * height * 4` bytes).
#[derive(Clone, Debug, PartialEq)]
pub struct TextureImage {
    pub path: PathBuf,
    pub width: u32,
    pub height: u32,
    pub rgba8: Vec<u8>,
}

/// Diffuse-only material. Textures are shared (`Arc`) between materials that use the same file.
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    pub name: String,
    /// Linear diffuse albedo, each channel in [0, 1].
    pub diffuse: [f32; 3],
    pub diffuse_texture: Option<Arc<TextureImage>>,
}

impl Material {
    /// The colour used when an OBJ has no material (MTL convention: Kd 0.8).
    pub const DEFAULT_DIFFUSE: [f32; 3] = [0.8, 0.8, 0.8];

    pub fn colour(name: &str, diffuse: [f32; 3]) -> Self {
        Self {
            name: name.to_owned(),
            diffuse,
            diffuse_texture: None,
        }
    }

    pub fn default_material() -> Self {
        Self::colour("default", Self::DEFAULT_DIFFUSE)
    }
}

/// A contiguous run of `Mesh::indices` drawn with one material.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DrawRange {
    /// Index into `Mesh::materials`.
    pub material: usize,
    pub first_index: u32,
    pub index_count: u32,
}

/// Axis-aligned bounding box. An empty box has `min > max` (see [`Aabb::EMPTY`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    pub min: Vec3,
    pub max: Vec3,
}

impl Default for Aabb {
    fn default() -> Self {
        Self::EMPTY
    }
}

impl Aabb {
    pub const EMPTY: Aabb = Aabb {
        min: Vec3::splat(f32::INFINITY),
        max: Vec3::splat(f32::NEG_INFINITY),
    };

    pub fn from_points(points: impl IntoIterator<Item = Vec3>) -> Self {
        let mut b = Self::EMPTY;
        for p in points {
            b.grow(p);
        }
        b
    }

    pub fn grow(&mut self, p: Vec3) {
        self.min = self.min.min(p);
        self.max = self.max.max(p);
    }

    pub fn is_empty(&self) -> bool {
        !(self.min.cmple(self.max).all())
    }

    pub fn center(&self) -> Vec3 {
        if self.is_empty() {
            Vec3::ZERO
        } else {
            (self.min + self.max) * 0.5
        }
    }

    /// Size along each axis (`max - min`); zero for an empty box.
    pub fn extent(&self) -> Vec3 {
        if self.is_empty() {
            Vec3::ZERO
        } else {
            self.max - self.min
        }
    }

    /// Length of the diagonal: the scene's characteristic scale for relative epsilons.
    pub fn diagonal(&self) -> f32 {
        self.extent().length()
    }

    pub fn radius(&self) -> f32 {
        0.5 * self.diagonal()
    }
}

/// What the loader counted and what it had to fix or skip.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LoadStats {
    /// `f` lines in the file (0 for procedural meshes, whose faces are not file lines).
    pub faces: usize,
    /// Triangles after triangulation, *before* degenerate ones were dropped. For an
    /// all-triangle OBJ this equals `faces`.
    pub triangles: usize,
    /// Triangles dropped for zero area (repeated or collinear corners; `obj::degeneracy`).
    pub dropped_zero_area: usize,
    /// Triangles dropped as slivers thinner than float precision of their own longest edge
    /// (`obj::SLIVER_RELATIVE_HEIGHT`).
    pub dropped_slivers: usize,
    /// Non-fatal problems (missing textures/MTL, unknown materials), human-readable.
    pub warnings: Vec<String>,
}

impl LoadStats {
    /// Every triangle the loader dropped, for any reason.
    pub fn dropped(&self) -> usize {
        self.dropped_zero_area + self.dropped_slivers
    }
}

/// Indexed triangle mesh, indices grouped by material (one [`DrawRange`] per used material).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    pub vertices: Vec<Vertex>,
    pub indices: Vec<u32>,
    pub ranges: Vec<DrawRange>,
    pub materials: Vec<Material>,
    pub bounds: Aabb,
    pub stats: LoadStats,
}

impl Mesh {
    /// Triangles actually drawn (after degenerate ones were dropped).
    pub fn triangle_count(&self) -> usize {
        self.indices.len() / 3
    }

    /// Corner positions of triangle `t`. Panics only if `t >= triangle_count()` or the mesh
    /// was built inconsistently (indices always come from the builder, which checks them).
    pub fn triangle(&self, t: usize) -> [Vec3; 3] {
        let i = &self.indices[3 * t..3 * t + 3];
        [
            self.vertices[i[0] as usize].pos(),
            self.vertices[i[1] as usize].pos(),
            self.vertices[i[2] as usize].pos(),
        ]
    }

    /// Material index of triangle `t` (from the draw ranges).
    pub fn material_of_triangle(&self, t: usize) -> Option<usize> {
        let first = (3 * t) as u64;
        self.ranges
            .iter()
            .find(|r| {
                first >= r.first_index as u64 && first < r.first_index as u64 + r.index_count as u64
            })
            .map(|r| r.material)
    }

    /// Vertices as the bytes the GPU buffer holds (little-endian f32, 32 bytes per vertex),
    /// built without `unsafe`.
    pub fn vertex_bytes(&self) -> Vec<u8> {
        let mut out = Vec::with_capacity(self.vertices.len() * std::mem::size_of::<Vertex>());
        for v in &self.vertices {
            for x in v.position.iter().chain(&v.normal).chain(&v.uv) {
                out.extend_from_slice(&x.to_le_bytes());
            }
        }
        out
    }

    /// Indices as little-endian u32 bytes (`VK_INDEX_TYPE_UINT32`).
    pub fn index_bytes(&self) -> Vec<u8> {
        self.indices.iter().flat_map(|i| i.to_le_bytes()).collect()
    }

    /// Whether any material has a diffuse texture (lets the renderer compile textures out).
    pub fn has_textures(&self) -> bool {
        self.materials.iter().any(|m| m.diffuse_texture.is_some())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn byte_layout_matches_repr_c() {
        let mesh = Mesh {
            vertices: vec![Vertex {
                position: [1.0, 2.0, 3.0],
                normal: [0.0, 1.0, 0.0],
                uv: [0.25, 0.75],
            }],
            indices: vec![0, 0, 0],
            ..Default::default()
        };
        let bytes = mesh.vertex_bytes();
        assert_eq!(bytes.len(), 32);
        let f = |o: usize| f32::from_le_bytes(bytes[o..o + 4].try_into().unwrap());
        assert_eq!(f(0), 1.0);
        assert_eq!(f(VERTEX_NORMAL_OFFSET as usize + 4), 1.0);
        assert_eq!(f(VERTEX_UV_OFFSET as usize + 4), 0.75);
        assert_eq!(mesh.index_bytes().len(), 12);
    }

    #[test]
    fn aabb_helpers() {
        let b = Aabb::from_points([Vec3::ZERO, Vec3::new(2.0, 4.0, 4.0)]);
        assert_eq!(b.center(), Vec3::new(1.0, 2.0, 2.0));
        assert_eq!(b.extent(), Vec3::new(2.0, 4.0, 4.0));
        assert_eq!(b.diagonal(), 6.0);
        assert!(Aabb::EMPTY.is_empty());
        assert_eq!(Aabb::EMPTY.diagonal(), 0.0);
    }
}
