//! Serialises `glam::Vec3` as `[x, y, z]` without enabling glam's `serde` feature.

use glam::Vec3;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

pub fn serialize<S: Serializer>(v: &Vec3, s: S) -> Result<S::Ok, S::Error> {
    v.to_array().serialize(s)
}

pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Vec3, D::Error> {
    <[f32; 3]>::deserialize(d).map(Vec3::from_array)
}
