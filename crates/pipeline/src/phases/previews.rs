//! Render: previews of the chosen attempt, when asked for and a renderer is configured. Each
//! attempt's previews are drawn on a thread of their own while the judge runs
//! ([`PreviewsBeside`]); the chosen attempt's are kept, and drawn now only when its thread gave
//! none. A renderer failure is a note in the report, not an error.

use std::collections::BTreeMap;
use std::sync::Arc;
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use scenethesis_render_api::{render_previews, RendererError, SceneRenderer};
use scenethesis_scene_graph::{Mesh, Scene};

use super::clock::StageClock;
use super::judge::Attempt;
use crate::stage::Stage;
use crate::GenerateOptions;

/// Preview files (name, PNG bytes), or why the renderer made none.
type Rendered = Result<Vec<(String, Vec<u8>)>, RendererError>;

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
    fn finish(self) -> Option<(Rendered, Duration)> {
        self.thread.join().ok()
    }
}

/// The chosen attempt's previews (file name, PNG bytes) and notes on what was skipped.
pub(crate) fn previews(
    renderer: Option<&dyn SceneRenderer>,
    best: &mut Attempt,
    options: &GenerateOptions,
    clock: &mut StageClock<'_>,
) -> (Vec<(String, Vec<u8>)>, Vec<String>) {
    if !options.previews {
        return (Vec::new(), Vec::new());
    }
    let Some(renderer) = renderer else {
        return (
            Vec::new(),
            vec!["previews skipped: no renderer configured".into()],
        );
    };
    let note = |result: &Rendered| {
        let count = result.as_ref().map_or(0, Vec::len);
        format!("{count} image(s) with {}", renderer.name())
    };
    let beside = best.previews_beside.take().and_then(PreviewsBeside::finish);
    let rendered = match beside {
        Some((rendered, took)) => {
            let note = format!("{}, drawn beside the judge", note(&rendered));
            clock.record(Stage::Render, best.round, took, &note);
            rendered
        }
        None => clock.run_infallible(
            Stage::Render,
            best.round,
            || render_previews(renderer, &best.scene, &best.meshes, options.preview_size),
            note,
        ),
    };
    match rendered {
        Ok(images) => (images, Vec::new()),
        Err(e) => (Vec::new(), vec![format!("previews skipped: {e}")]),
    }
}
