//! Experiments that measure the method against ground truth, kept apart from the production
//! pipeline (they render with the GPU renderer and re-run stages on purpose-built inputs):
//!
//! - [`roundtrip`]: a saved scene's guidance is rendered, optionally perturbed the way real
//!   models err, lifted back to boxes by the vision geometry, and each recovered object is
//!   compared with the truth (`scenethesis roundtrip DIR`).
//! - [`ablation`]: the paper's ablation of the physics-aware optimization on the same
//!   guidance: raw boxes, after correspondence, after collisions, after stability
//!   (`scenethesis roundtrip DIR --ablation`).
//!
//! `cargo xtask bench --json roundtrip` runs both over the benchmark prompts.
//!
//! ```
//! use scenethesis_experiments::roundtrip::{Perturbation, RoundtripOptions};
//!
//! // The options of `scenethesis roundtrip DIR --perturb default --seed 3`.
//! let options = RoundtripOptions {
//!     perturb: Perturbation::Default,
//!     seed: 3,
//!     ..RoundtripOptions::default()
//! };
//! assert_eq!(options.size, RoundtripOptions::default().size);
//! ```

#![warn(missing_docs)]

pub mod ablation;
pub mod roundtrip;
