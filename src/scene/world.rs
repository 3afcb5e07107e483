//! The scene as the renderer takes it: mesh, camera, spot light (and its path), ambient light.

use super::camera::Camera;
use super::light::SpotLight;
use super::mesh::Mesh;
use super::object::DynamicObject;
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
    /// Rigid objects moving along their paths, drawn apart from `mesh` (which holds only
    /// what stands still); `Renderer::set_time` poses them.
    pub objects: Vec<DynamicObject>,
}

impl Scene {
    /// Everything at `time` seconds as one mesh: `mesh` with every moving object placed.
    pub fn posed_mesh(&self, time: f32) -> super::mesh::Mesh {
        super::object::posed_mesh(&self.mesh, &self.objects, time)
    }

    /// The scene as it is `time` seconds in, with nothing left to move: every object placed in
    /// the mesh, the light where its path has it. The mesh keeps [`Scene::bounds`] (everywhere
    /// an object goes), so sizes relative to the scene (the AO radius) are the renderer's.
    pub fn posed(&self, time: f32) -> Scene {
        if self.objects.is_empty() && self.light_path.is_none() {
            return self.clone();
        }
        let mut mesh = self.posed_mesh(time);
        mesh.bounds = self.bounds();
        Scene {
            mesh,
            light: self
                .light_path
                .as_ref()
                .map_or(self.light, |p| p.light_at(&self.light, time)),
            light_path: None,
            objects: Vec::new(),
            ..self.clone()
        }
    }

    /// Bounds of what stands still and of everywhere a moving object goes.
    pub fn bounds(&self) -> super::mesh::Aabb {
        let mut b = self.mesh.bounds;
        for o in &self.objects {
            let s = o.swept_bounds();
            if !s.is_empty() {
                b.grow(s.min);
                b.grow(s.max);
            }
        }
        b
    }

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
