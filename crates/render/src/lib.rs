//! Headless rendering of posed meshes with wgpu: colour, metric depth and instance-id images
//! from a scene-graph `Camera`, on real GPUs or Mesa's software drivers.
