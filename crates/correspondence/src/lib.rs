//! 2D/3D correspondences between a rendered object and a guidance image: the matches that the
//! pose-alignment loss consumes, behind a trait so that matching models can be swapped.
