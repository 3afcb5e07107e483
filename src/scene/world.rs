//! The scene as the renderer takes it: mesh, camera, spot light, ambient light.

use super::camera::Camera;
use super::light::SpotLight;
use super::mesh::Mesh;
use glam::Vec3;

/// Everything the renderer needs for one scene.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    pub name: String,
    pub mesh: Mesh,
    pub camera: Camera,
    pub light: SpotLight,
    /// Constant ambient radiance added in composite (RGB).
    pub ambient: Vec3,
}
