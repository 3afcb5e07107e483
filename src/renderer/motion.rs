//! Moving objects on the renderer's side: each object's transform for the next frame (set by
//! `Renderer::set_time`), the one the last frame drew it with, the frame's poses (the G-buffer
//! writes the motion between them), and whether the light can see what moved.

use crate::resources::scene_gpu::Pose;
use crate::scene::{Aabb, DynamicObject, SpotLight};
use glam::{Affine3A, Vec4};

pub struct Motion {
    /// Where each object is for the next frame.
    next: Vec<Affine3A>,
    /// Where the last frame drew it; meaningless until `has_drawn` (before the first frame
    /// and after a cut). Sized once: frames copy into it, nothing is allocated per frame.
    drawn: Vec<Affine3A>,
    has_drawn: bool,
    /// Counts the frames on which something moved: the frame-skipping key of geometry.
    revision: u64,
}

impl Motion {
    /// Every object at the start of its path.
    pub fn new(objects: &[DynamicObject]) -> Self {
        let next: Vec<Affine3A> = objects.iter().map(|o| o.transform_at(0.0)).collect();
        Self {
            drawn: next.clone(),
            next,
            has_drawn: false,
            revision: 0,
        }
    }

    /// Place every object where its path has it `time` seconds in.
    pub fn set_time(&mut self, objects: &[DynamicObject], time: f32) {
        for (t, o) in self.next.iter_mut().zip(objects) {
            *t = o.transform_at(time);
        }
    }

    /// Object `i`'s pose for the next frame: last frame's transform as `before`, or `now`
    /// when last frame's G-buffer is not reused (its motion is then 0).
    fn pose(&self, i: usize, history_valid: bool) -> Pose {
        let now = self.next[i];
        let before = if self.has_drawn && history_valid {
            self.drawn[i]
        } else {
            now
        };
        Pose { now, before }
    }

    /// Write the next frame's poses into `out` (one per object) and count those that moved.
    pub fn write_poses(&self, history_valid: bool, out: &mut [Pose]) -> usize {
        let mut moved = 0;
        for (i, p) in out.iter_mut().enumerate().take(self.next.len()) {
            *p = self.pose(i, history_valid);
            moved += usize::from(p.moved());
        }
        moved
    }

    /// The frame-skipping key of geometry for the next frame: it changes on every frame that
    /// moves something.
    pub fn revision(&self, history_valid: bool) -> u64 {
        let moved = (0..self.next.len()).any(|i| self.pose(i, history_valid).moved());
        self.revision + u64::from(moved)
    }

    /// The next frame was recorded with these transforms.
    pub fn drawn(&mut self, moved: usize) {
        if moved > 0 {
            self.revision += 1;
        }
        self.drawn.copy_from_slice(&self.next);
        self.has_drawn = true;
    }

    /// Forget last frame's transforms (a camera cut, a resize): the next frame has no motion.
    pub fn forget(&mut self) {
        self.has_drawn = false;
    }
}

/// What moved since last frame, as the reprojection's invalidation reads it: a box around
/// every moved object at both of its poses, and that box's footprint on the shadow map.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Moved {
    pub count: u32,
    pub bounds: Aabb,
    /// (x0, y0, x1, y1) in shadow-map texels; the whole map when part of the box is behind
    /// the light.
    pub light_rect: [f32; 4],
    /// The same on the screen [px] (the whole screen when part of it is behind the eye).
    pub screen_rect: [f32; 4],
}

/// Where the moved box is seen from: the light (its map's side) and the camera (its
/// view-projection and the render size).
pub struct Views {
    pub light: SpotLight,
    pub map_size: u32,
    pub camera: glam::Mat4,
    pub size: (u32, u32),
}

/// What moved in `poses`, None when nothing did.
pub fn moved(objects: &[DynamicObject], poses: &[Pose], views: &Views) -> Option<Moved> {
    let mut bounds = Aabb::EMPTY;
    let mut count = 0;
    for (o, p) in objects.iter().zip(poses).filter(|(_, p)| p.moved()) {
        count += 1;
        for t in [p.now, p.before] {
            let b = o.bounds(&t);
            bounds.grow(b.min);
            bounds.grow(b.max);
        }
    }
    let map = views.map_size as f32;
    let (w, h) = (views.size.0 as f32, views.size.1 as f32);
    (count > 0).then(|| Moved {
        count,
        bounds,
        light_rect: footprint(&views.light.view_proj(), &bounds, (map, map)),
        screen_rect: footprint(&views.camera, &bounds, (w, h)),
    })
}

/// Texels of a `size` map (or pixels of a screen) that the box covers seen through
/// `view_proj`.
fn footprint(view_proj: &glam::Mat4, b: &Aabb, size: (f32, f32)) -> [f32; 4] {
    let mut rect = [
        f32::INFINITY,
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::NEG_INFINITY,
    ];
    for i in 0..8 {
        let pick = |bit: usize, lo: f32, hi: f32| if i & bit == 0 { lo } else { hi };
        let c = *view_proj
            * Vec4::new(
                pick(1, b.min.x, b.max.x),
                pick(2, b.min.y, b.max.y),
                pick(4, b.min.z, b.max.z),
                1.0,
            );
        // A corner at or behind the light's eye projects nowhere: the box may cover anything.
        if c.w.is_nan() || c.w <= 0.0 {
            return [0.0, 0.0, size.0, size.1];
        }
        let t = (c.truncate().truncate() / c.w * 0.5 + 0.5) * glam::Vec2::new(size.0, size.1);
        rect = [
            rect[0].min(t.x),
            rect[1].min(t.y),
            rect[2].max(t.x),
            rect[3].max(t.y),
        ];
    }
    rect
}

/// Whether `light`'s frustum can see an object that moved in `poses` (at either pose): the
/// light view must then be rendered again.
pub fn light_sees_motion(light: &SpotLight, objects: &[DynamicObject], poses: &[Pose]) -> bool {
    let view_proj = light.view_proj();
    objects.iter().zip(poses).any(|(o, p)| {
        p.moved()
            && [p.now, p.before]
                .iter()
                .any(|t| in_frustum(&view_proj, &o.bounds(t)))
    })
}

/// Whether a box may meet the frustum of `view_proj` (Vulkan clip space: x, y in [-w, w],
/// depth in [0, w]): false only when all eight corners lie beyond one clip plane.
pub fn in_frustum(view_proj: &glam::Mat4, b: &Aabb) -> bool {
    if b.is_empty() {
        return false;
    }
    let corners: [Vec4; 8] = std::array::from_fn(|i| {
        let pick = |bit: usize, lo: f32, hi: f32| if i & bit == 0 { lo } else { hi };
        *view_proj
            * Vec4::new(
                pick(1, b.min.x, b.max.x),
                pick(2, b.min.y, b.max.y),
                pick(4, b.min.z, b.max.z),
                1.0,
            )
    });
    let planes: [fn(&Vec4) -> bool; 6] = [
        |c| c.x < -c.w,
        |c| c.x > c.w,
        |c| c.y < -c.w,
        |c| c.y > c.w,
        |c| c.z < 0.0,
        |c| c.z > c.w,
    ];
    !planes.iter().any(|out| corners.iter().all(out))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{cornell_light, ObjectKey};
    use glam::Vec3;

    fn ball(at: [f32; 3], to: [f32; 3]) -> DynamicObject {
        DynamicObject {
            name: "ball".into(),
            mesh: crate::scene::sphere(),
            keys: vec![
                ObjectKey {
                    time: 0.0,
                    position: at,
                    rotation_deg: [0.0; 3],
                },
                ObjectKey {
                    time: 1.0,
                    position: to,
                    rotation_deg: [0.0; 3],
                },
            ],
        }
    }

    #[test]
    fn poses_carry_last_frame_and_count_what_moved() {
        let objects = [ball([0.0; 3], [1.0, 0.0, 0.0])];
        let mut m = Motion::new(&objects);
        let mut p = [Pose::STILL];
        let moved = m.write_poses(false, &mut p);
        assert_eq!((p[0].now, moved), (Affine3A::IDENTITY, 0));
        m.drawn(moved);
        m.set_time(&objects, 0.5);
        let moved = m.write_poses(true, &mut p);
        assert_eq!(moved, 1);
        assert_eq!(p[0].before, Affine3A::IDENTITY);
        assert_eq!(p[0].now.translation, Vec3::new(0.5, 0.0, 0.0).into());
        // Without a reused history the frame has no motion.
        assert_eq!(m.write_poses(false, &mut p), 0);
        let r = m.revision(true);
        m.drawn(moved);
        assert_eq!(m.revision(true), r, "held still: the key stays");
    }

    #[test]
    fn the_light_sees_only_what_its_cone_holds() {
        // The Cornell light looks straight down from under the ceiling.
        let light = cornell_light();
        let below = [ball([0.0, 0.5, 0.0], [0.1, 0.5, 0.0])];
        let above = [ball([0.0, 5.0, 0.0], [0.1, 5.0, 0.0])];
        let mut poses = [Pose::STILL];
        let mut m = Motion::new(&below);
        m.drawn(0);
        m.set_time(&below, 1.0);
        m.write_poses(true, &mut poses);
        assert!(light_sees_motion(&light, &below, &poses));
        let mut m = Motion::new(&above);
        m.drawn(0);
        m.set_time(&above, 1.0);
        m.write_poses(true, &mut poses);
        assert!(!light_sees_motion(&light, &above, &poses));
        // Still objects are never a reason.
        assert!(!light_sees_motion(&light, &below, &[Pose::STILL]));
    }
}
