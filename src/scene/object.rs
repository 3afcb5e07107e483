//! Rigid objects that move: a mesh in its own space and keyframes of its position and
//! rotation over time (scene files' `[[mesh.keyframes]]`). The renderer draws each with its
//! transform of this frame and of the last one, so the G-buffer knows where every pixel's
//! surface point was (its motion) and the reprojection follows moving surfaces.

use super::builder::MeshBuilder;
use super::mesh::{Aabb, Mesh};
use glam::{Affine3A, EulerRot, Quat, Vec3};

/// Where an object is `time` seconds into its path. Between keys position and Euler angles
/// interpolate linearly; before the first and after the last the object holds.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ObjectKey {
    pub time: f32,
    pub position: [f32; 3],
    /// Degrees about x, then y, then z (default 0).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub rotation_deg: [f32; 3],
}

fn is_zero(v: &[f32; 3]) -> bool {
    *v == [0.0; 3]
}

/// A moving rigid object.
#[derive(Clone, Debug, PartialEq)]
pub struct DynamicObject {
    pub name: String,
    /// In the object's own space (scale and albedo already applied).
    pub mesh: Mesh,
    /// At least one, times finite and non-decreasing (checked by the scene file).
    pub keys: Vec<ObjectKey>,
}

/// Rotation of Euler angles in degrees about x, then y, then z.
pub fn euler_deg(r: [f32; 3]) -> Quat {
    let [x, y, z] = r.map(f32::to_radians);
    Quat::from_euler(EulerRot::ZYX, z, y, x)
}

impl DynamicObject {
    /// Object-to-world transform `time` seconds into the path (clamped to its keys).
    pub fn transform_at(&self, time: f32) -> Affine3A {
        let (position, rotation) = self.pose_at(time);
        Affine3A::from_rotation_translation(euler_deg(rotation), Vec3::from(position))
    }

    fn pose_at(&self, time: f32) -> ([f32; 3], [f32; 3]) {
        let Some(first) = self.keys.first() else {
            return ([0.0; 3], [0.0; 3]);
        };
        let at = |k: &ObjectKey| (k.position, k.rotation_deg);
        if time <= first.time {
            return at(first);
        }
        // The segment [a, b] holding `time`; equal times (a jump) take the later key.
        let Some(i) = self.keys.windows(2).position(|w| time < w[1].time) else {
            return at(self.keys.last().unwrap_or(first));
        };
        let (a, b) = (&self.keys[i], &self.keys[i + 1]);
        let span = b.time - a.time;
        let s = if span > 0.0 {
            ((time - a.time) / span).clamp(0.0, 1.0)
        } else {
            1.0
        };
        let lerp = |u: [f32; 3], v: [f32; 3]| Vec3::from(u).lerp(Vec3::from(v), s).to_array();
        (
            lerp(a.position, b.position),
            lerp(a.rotation_deg, b.rotation_deg),
        )
    }

    /// Bounds of the mesh placed by `to_world` (the eight corners of its own box moved).
    pub fn bounds(&self, to_world: &Affine3A) -> Aabb {
        let b = self.mesh.bounds;
        if b.is_empty() {
            return b;
        }
        Aabb::from_points((0..8).map(|i| {
            let pick = |bit: usize, lo: f32, hi: f32| if i & bit == 0 { lo } else { hi };
            to_world.transform_point3(Vec3::new(
                pick(1, b.min.x, b.max.x),
                pick(2, b.min.y, b.max.y),
                pick(4, b.min.z, b.max.z),
            ))
        }))
    }

    /// Bounds over every key's pose (where the object can be, up to the interpolation of
    /// rotations between keys, which the corners of a sphere-like mesh's box cover).
    pub fn swept_bounds(&self) -> Aabb {
        let mut out = Aabb::EMPTY;
        for k in &self.keys {
            let b = self.bounds(&self.transform_at(k.time));
            if !b.is_empty() {
                out.grow(b.min);
                out.grow(b.max);
            }
        }
        out
    }
}

/// `statics` with every object placed at `time`, as one mesh (the CPU's view of a moving
/// scene: ray casts, the ground truth).
pub fn posed_mesh(statics: &Mesh, objects: &[DynamicObject], time: f32) -> Mesh {
    if objects.is_empty() {
        return statics.clone();
    }
    let mut b = MeshBuilder::new();
    b.append(statics, 1.0, Vec3::ZERO);
    for o in objects {
        let t = o.transform_at(time);
        let (_, rotation, offset) = t.to_scale_rotation_translation();
        b.append_placed(&o.mesh, 1.0, rotation, offset, None);
    }
    b.build()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::procedural::sphere;

    fn ball() -> DynamicObject {
        DynamicObject {
            name: "ball".into(),
            mesh: sphere(),
            keys: vec![
                ObjectKey {
                    time: 1.0,
                    position: [0.0, 1.0, 0.0],
                    rotation_deg: [0.0; 3],
                },
                ObjectKey {
                    time: 3.0,
                    position: [2.0, 1.0, 0.0],
                    rotation_deg: [0.0, 0.0, -90.0],
                },
            ],
        }
    }

    #[test]
    fn poses_interpolate_and_hold() {
        let b = ball();
        let at = |t: f32| b.transform_at(t).transform_point3(Vec3::ZERO);
        assert_eq!(at(0.0), Vec3::new(0.0, 1.0, 0.0));
        assert!(at(2.0).abs_diff_eq(Vec3::new(1.0, 1.0, 0.0), 1e-6));
        assert_eq!(at(9.0), Vec3::new(2.0, 1.0, 0.0));
        // Halfway, a quarter turn's half about z: +x goes to (cos 45, -sin 45).
        let x = b.transform_at(2.0).transform_vector3(Vec3::X);
        let h = std::f32::consts::FRAC_1_SQRT_2;
        assert!(x.abs_diff_eq(Vec3::new(h, -h, 0.0), 1e-6), "{x}");
        let swept = b.swept_bounds();
        assert!(swept.min.abs_diff_eq(Vec3::new(-1.0, 0.0, -1.0), 1e-5));
        assert!(swept.max.abs_diff_eq(Vec3::new(3.0, 2.0, 1.0), 1e-5));
    }

    #[test]
    fn the_posed_mesh_holds_every_object_where_it_is() {
        let statics = crate::scene::cornell_box().mesh;
        let m = posed_mesh(&statics, &[ball()], 2.0);
        assert_eq!(
            m.triangle_count(),
            statics.triangle_count() + sphere().triangle_count()
        );
        let tail = &m.vertices[statics.vertices.len()..];
        for v in tail {
            assert!((v.pos().distance(Vec3::new(1.0, 1.0, 0.0)) - 1.0).abs() < 1e-5);
        }
    }
}
