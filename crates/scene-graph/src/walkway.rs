//! Facts of the walkway that every crate measuring or planning one must share.

/// The radius (m) of the robot the Walk and Reach metrics move through a scene: half of its
/// 0.3 m diameter (`metrics.md`). The guide grows footprints by it when it keeps a walkway
/// open, and the metrics erode the floor by it; both read this constant.
pub const ROBOT_RADIUS: f64 = 0.15;

#[cfg(test)]
mod tests {
    /// `metrics.md` fixes the robot at 0.3 m diameter; the guide and the metrics must agree.
    #[test]
    fn the_robot_is_thirty_centimetres_wide() {
        assert_eq!(2.0 * super::ROBOT_RADIUS, 0.3);
    }
}
