//! Per-frame constants: the `Frame` block (shaders/include/frame.glsl) filled member by
//! member through the struct build.rs generates from it.

use crate::config::{IndirectInput, RenderConfig};
use crate::scene::{Camera, SpotLight};
pub use crate::shaders::FrameBlock;
use glam::{Mat4, Vec3};

/// Everything that changes per frame, besides the configuration.
pub struct FrameInputs<'a> {
    pub camera: &'a Camera,
    /// Last frame's camera view-projection (eq 1); equal to this frame's on the first frame.
    pub prev_view_proj: Mat4,
    /// Last frame's eye; this frame's on the first frame.
    pub prev_camera_pos: Vec3,
    pub light: &'a SpotLight,
    pub ambient: Vec3,
    pub frame: u64,
    /// Bounding radius of the scene: the AO radius is relative to it.
    pub scene_radius: f32,
    /// What moved since last frame (`motion::Moved`), if anything did.
    pub moved: Option<super::motion::Moved>,
    /// Test hook (`Renderer::plant_nan`): this pixel's indirect estimates are NaN this frame.
    pub planted_nan: Option<[u32; 2]>,
    /// The most workgroups a work list's dispatch has in x: the device's
    /// maxComputeWorkGroupCount[0], or less by a test hook (`Renderer::limit_list_groups`).
    pub max_groups_x: u32,
}

/// The per-frame uniform block (`Frame` in shaders/include/frame.glsl), filled member by member.
pub fn frame_block(config: &RenderConfig, f: &FrameInputs<'_>) -> FrameBlock {
    let aspect = config.width as f32 / config.height as f32;
    let light = f.light;
    let t = &config.temporal;
    let (pcf_kernel, pcf_count) = config.pcf.shader_params();
    let (epsilon, epsilon_absolute) = t.epsilon.shader_params();
    let ind = &config.indirect;
    let view_proj = f.camera.view_proj(aspect);
    FrameBlock {
        view_proj: view_proj.to_cols_array(),
        prev_view_proj: f.prev_view_proj.to_cols_array(),
        light_view_proj: light.view_proj().to_cols_array(),
        camera_pos: f.camera.position.to_array(),
        prev_camera_pos: f.prev_camera_pos.to_array(),
        history_resample: t.resample.code(),
        tan_half_fov: (0.5 * f.camera.vfov_deg).to_radians().tan(),
        light_pos: light.position.to_array(),
        light_cos_outer: light.outer_deg.to_radians().cos(),
        light_dir: light.direction.normalize_or(Vec3::NEG_Y).to_array(),
        light_cos_inner: light.inner_deg.to_radians().cos(),
        light_intensity: light.intensity.to_array(),
        light_near: light.near,
        ambient: f.ambient.to_array(),
        light_far: light.far,
        size: [config.width, config.height],
        frame_index: f.frame as u32,
        rotation_limit: t.rotation_limit,
        // Floored: relative radii multiply it, and a point scene must not give them zero.
        scene_radius: f.scene_radius.max(f32::MIN_POSITIVE),
        light_tan_half_fov: (0.5 * light.frustum_fov_deg()).to_radians().tan(),
        shadow_map_size: config.rsm_size as f32,
        pcf_radius: config.pcf.radius_texels,
        pcf_kernel,
        pcf_count,
        accumulate_mode: t.accumulate.code(),
        accumulate_param: t.accumulate.parameter(),
        epsilon,
        epsilon_absolute,
        // Exact equality: an unmoved camera reuses each history texel as is, decided here
        // rather than by a pixel threshold on eq 1, whose fp32 error grows with coordinates.
        camera_static: (view_proj == f.prev_view_proj) as u32,
        indirect_input: indirect_input(f.planted_nan, ind.input, config.width),
        moved_light_rect: f.moved.map_or([0.0; 4], |m| m.light_rect),
        moved_screen_rect: f.moved.map_or([0.0; 4], |m| m.screen_rect),
        moved_min: f.moved.map_or([0.0; 3], |m| m.bounds.min.to_array()),
        moved_count: f.moved.map_or(0, |m| m.count),
        moved_max: f.moved.map_or([0.0; 3], |m| m.bounds.max.to_array()),
        max_groups_x: f.max_groups_x.max(1),
    }
}

/// What the indirect light gathers from: the RSM, a test ramp, or NaN at a planted pixel.
fn indirect_input(planted_nan: Option<[u32; 2]>, input: IndirectInput, width: u32) -> u32 {
    match (planted_nan, input) {
        // Pixel indices stay below 2^28 (MAX_SIZE^2); 2 + index fits a u32.
        (Some([x, y]), _) => 2 + y * width + x,
        (None, IndirectInput::Ramp) => 1,
        (None, IndirectInput::Gather) => 0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::cornell_box;

    /// `camera_static` is set exactly when last frame's view-projection equals this one's:
    /// the smallest representable change of one entry clears it.
    #[test]
    fn camera_static_means_an_identical_view_projection() {
        let scene = cornell_box();
        let config = RenderConfig::default();
        let aspect = config.width as f32 / config.height as f32;
        let current = scene.camera.view_proj(aspect);
        let mut moved = current.to_cols_array();
        moved[12] = f32::from_bits(moved[12].to_bits() + 1);
        let block = |prev_view_proj| {
            frame_block(
                &config,
                &FrameInputs {
                    camera: &scene.camera,
                    prev_view_proj,
                    prev_camera_pos: scene.camera.position,
                    light: &scene.light,
                    ambient: scene.ambient,
                    frame: 1,
                    scene_radius: 1.0,
                    moved: None,
                    planted_nan: None,
                    max_groups_x: 65535,
                },
            )
        };
        assert_eq!(block(current).camera_static, 1);
        assert_eq!(block(Mat4::from_cols_array(&moved)).camera_static, 0);
    }
}
