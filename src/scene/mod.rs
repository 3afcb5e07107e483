//! Scenes on the CPU: OBJ/MTL loading with validation, procedural scenes, camera, spot
//! light, camera paths and ray queries for reference values. No Vulkan here.
//!
//! Conventions: y up, metres for the built-in scenes, right-handed view, Vulkan clip space
//! (depth 0..1, NDC y = -1 at the top row). Triangles of procedural meshes are wound
//! counter-clockwise seen from the side their normal points to; loaded meshes keep the
//! file's winding (most OBJ exporters use the same rule).

pub mod accel;
mod builder;
mod camera;
pub mod decimate;
mod error;
pub mod flat_bvh;
mod framing;
pub mod input;
mod light;
mod mesh;
mod normals;
mod obj;
mod object;
pub mod path;
mod procedural;
mod raycast;
mod scene_file;
mod scene_load;
mod serde_vec3;
mod spec;
mod texture;
mod toml_locate;
mod validate;
mod world;

pub use builder::MeshBuilder;
pub use camera::{depth_range_problem, pixel_to_ndc, Camera, MAX_DEPTH_RATIO};
pub use error::SceneError;
pub use light::{check_intensity, max_intensity, LightKind, SpotLight, MAX_SCENE_IRRADIANCE};
pub use mesh::{
    Aabb, DrawRange, LoadStats, Material, Mesh, TextureImage, Vertex, VERTEX_NORMAL_OFFSET,
    VERTEX_UV_OFFSET,
};
pub use normals::area_weighted_normals;
pub use obj::{degeneracy, load_obj, Degeneracy, SLIVER_RELATIVE_HEIGHT};
pub use object::{euler_deg, posed_mesh, DynamicObject, ObjectKey};
pub use path::{CameraPath, Keyframe, LightPath, Orbit};
pub use procedural::{
    box_room, cornell_box, cornell_camera, cornell_light, pyramids, sphere, tilted_quad, uv_sphere,
    CORNELL_GREEN, CORNELL_RED, CORNELL_WHITE,
};
pub use raycast::{occlusion_span, Hit, OCCLUSION_RELATIVE_OFFSET, OCCLUSION_ULPS};
pub use scene_file::{CameraEntry, LightEntry, MeshEntry, OrbitEntry, SceneFile, SPHERE};
pub use scene_load::{
    build as build_scene_file, is_scene_file, load as load_scene_with_paths, load_scene,
    load_scene_file, LoadedScene,
};
pub use spec::{
    asset_dir_from_env, list_assets, load_model, resolve_model, ASSETS_ENV, BUILTIN_SCENES,
};
pub use validate::{scene_size_problem, HUGE_COORDINATE, MIN_SCENE_RADIUS};
pub use world::Scene;
