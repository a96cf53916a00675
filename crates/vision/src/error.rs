use thiserror::Error;

/// Why a guidance image could not be lifted to 3D.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum LiftError {
    /// The camera looks up or level, so the floor is not in view and objects cannot be placed
    /// on it by single-view metrology.
    #[error("the camera looks level or upward (view direction y = {forward_y:.3}); expected a camera looking down at the floor")]
    CameraNotLookingDown {
        /// The vertical component of the camera's unit view direction.
        forward_y: f64,
    },
    /// The camera is below the floor or on it.
    #[error("the camera is at height {height:.3} m; expected it above the floor (y > 0)")]
    CameraBelowFloor {
        /// The camera's height above the floor in metres.
        height: f64,
    },
    /// A value of the options is outside its range.
    #[error("lift option `{field}` is {value}; expected {expected}")]
    BadOption {
        /// The option's name.
        field: &'static str,
        /// Its value.
        value: f64,
        /// What was expected.
        expected: &'static str,
    },
}
