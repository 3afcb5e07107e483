//! The scene as the renderer takes it: mesh, camera, spot light (and its path), ambient light.

use super::camera::Camera;
use super::light::SpotLight;
use super::mesh::Mesh;
use super::path::{LightPath, Orbit};
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
    /// Where `--path orbit` goes; None: around the mesh from outside ([`Scene::orbit`]).
    pub orbit: Option<Orbit>,
    /// Where the light moves over time (scene files' `[[light_keyframes]]`, `--light-path`);
    /// `Renderer::set_time` poses it. None: the light stays.
    pub light_path: Option<LightPath>,
}

impl Scene {
    /// The scene's orbit: its own, or a turn around the mesh's centre from outside (around
    /// the camera's target for an empty mesh).
    pub fn orbit(&self) -> Orbit {
        self.orbit.unwrap_or_else(|| {
            Orbit::around(if self.mesh.bounds.is_empty() {
                self.camera.target
            } else {
                self.mesh.bounds.center()
            })
        })
    }
}
