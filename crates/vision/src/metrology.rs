//! Phase 2 without depth: single-view metrology under a known camera.
//!
//! An object standing on the floor touches it along the bottom edge of its mask. The ray through
//! each column's lowest mask pixel meets the floor plane (y = 0) at a contact point; the object's
//! visible face is taken as the vertical surface above those contacts, so every mask pixel of the
//! column lifts to the point where its ray crosses that vertical. Heights and widths follow from
//! the camera geometry alone, with no depth model.

use std::collections::BTreeMap;

use nalgebra::{Point2, Point3, Vector3};
use scenethesis_imagery::{Camera, Mask};

use crate::points::median;
use crate::LiftError;

/// Checks that `camera` is above the floor and looks down at it.
pub fn check_camera(camera: &Camera) -> Result<(), LiftError> {
    if camera.position.y.is_nan() || camera.position.y <= 0.0 {
        return Err(LiftError::CameraBelowFloor {
            height: camera.position.y,
        });
    }
    let forward_y = camera.forward().y;
    if forward_y.is_nan() || forward_y >= -0.02 {
        return Err(LiftError::CameraNotLookingDown { forward_y });
    }
    Ok(())
}

/// Where the ray through `pixel` meets the floor plane y = 0; `None` when it goes up or level.
pub fn floor_hit(camera: &Camera, pixel: &Point2<f64>) -> Option<Point3<f64>> {
    let dir = camera.unproject(pixel, 1.0) - camera.position;
    if dir.y >= -1e-9 {
        return None;
    }
    let s = -camera.position.y / dir.y;
    Some(camera.position + dir * s)
}

/// The world points of an object standing on the floor, lifted from its mask alone.
///
/// When the object's `height` is known (a size prior), a pixel that would lift above it lies on
/// the object's top face instead, and is lifted onto the horizontal plane at that height.
///
/// Columns whose floor contact lies more than 25 % nearer or farther than the median contact
/// distance (a bottom edge hidden behind another object) use the median instead.
pub fn floor_contact_points(
    camera: &Camera,
    mask: &Mask,
    stride: u32,
    height: Option<f64>,
) -> Result<Vec<Point3<f64>>, LiftError> {
    check_camera(camera)?;
    let stride = stride.max(1);
    // The lowest mask pixel (largest v) of every column.
    let mut bottom: BTreeMap<u32, u32> = BTreeMap::new();
    for (u, v) in mask.pixels() {
        let e = bottom.entry(u).or_insert(v);
        *e = (*e).max(v);
    }
    let horizontal =
        |p: &Point3<f64>| Vector3::new(p.x - camera.position.x, 0.0, p.z - camera.position.z);
    let mut contacts: BTreeMap<u32, Point3<f64>> = BTreeMap::new();
    for (&u, &v) in &bottom {
        // The bottom edge of the lowest pixel touches the floor.
        if let Some(p) = floor_hit(camera, &Point2::new(u as f64 + 0.5, v as f64 + 1.0)) {
            contacts.insert(u, p);
        }
    }
    let mut distances: Vec<f64> = contacts.values().map(|p| horizontal(p).norm()).collect();
    let Some(med) = median(&mut distances) else {
        return Ok(Vec::new());
    };
    let mut out = Vec::new();
    for (u, v) in mask.pixels() {
        if u % stride != 0 || v % stride != 0 {
            continue;
        }
        let Some(contact) = contacts.get(&u) else {
            continue;
        };
        let mut h = horizontal(contact);
        let dist = h.norm();
        if dist < 1e-9 {
            continue;
        }
        if (dist - med).abs() > 0.25 * med {
            h *= med / dist;
        }
        // The vertical plane through the contact, facing the camera horizontally.
        let n = h.normalize();
        let dir =
            camera.unproject(&Point2::new(u as f64 + 0.5, v as f64 + 0.5), 1.0) - camera.position;
        let denom = n.dot(&dir);
        if denom <= 1e-9 {
            continue;
        }
        let s = n.dot(&h) / denom;
        let mut p = camera.position + dir * s;
        if let Some(top) = height.filter(|&t| p.y > t && dir.y < -1e-9 && camera.position.y > t) {
            // On the top face: where the ray crosses the plane y = top.
            p = camera.position + dir * ((top - camera.position.y) / dir.y);
        }
        out.push(p);
    }
    Ok(out)
}
