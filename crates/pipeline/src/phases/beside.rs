//! Previews drawn beside the judge: each attempt's previews on a thread of their own, at the
//! lowest priority, while the judge scores the attempt; [`previews`](super::previews) keeps
//! the delivered attempt's.

use std::collections::BTreeMap;
use std::sync::Arc;
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use scenethesis_render_api::{render_previews, RendererError, SceneRenderer};
use scenethesis_scene_graph::{Mesh, Scene};

/// Preview files (name, PNG bytes), or why the renderer made none.
pub(crate) type Rendered = Result<Vec<(String, Vec<u8>)>, RendererError>;

/// One attempt's previews, being drawn on a thread of their own at the lowest priority while
/// the judge scores the attempt.
///
/// The judge's stability simulation keeps one core and leaves the other idle once its
/// collision checks end; drawing the previews there hides most of their time when the attempt
/// is accepted (most are). The images are the ones the render stage would draw afterwards:
/// the same scene, meshes and renderer. An attempt that is not delivered lets its thread run
/// out unread.
pub(crate) struct PreviewsBeside {
    thread: JoinHandle<(Rendered, Duration)>,
}

impl PreviewsBeside {
    /// Starts drawing the previews of `scene` (a copy of it and of its `meshes`) at `size`.
    pub(crate) fn start(
        renderer: Arc<dyn SceneRenderer>,
        scene: &Scene,
        meshes: &BTreeMap<String, Mesh>,
        size: [u32; 2],
    ) -> Self {
        let (scene, meshes) = (scene.clone(), meshes.clone());
        let thread = std::thread::spawn(move || {
            super::run_at_lowest_priority();
            let started = Instant::now();
            let rendered = render_previews(renderer.as_ref(), &scene, &meshes, size);
            (rendered, started.elapsed())
        });
        Self { thread }
    }

    /// Waits for the previews and says how long drawing them took; `None` when the thread
    /// panicked.
    pub(crate) fn finish(self) -> Option<(Rendered, Duration)> {
        self.thread.join().ok()
    }
}
