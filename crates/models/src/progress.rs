//! Progress of a model's answer while it streams in: the client reports how much has arrived
//! with [`report_answer_progress`]; whoever shows progress (the pipeline's stage display)
//! listens for the duration of some work with [`with_answer_listener`]. Listeners are per
//! thread (a client reports on the thread that called it), so parallel runs each hear their own.

use std::cell::RefCell;
use std::time::Duration;

/// How much of a streamed answer has arrived.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct AnswerProgress {
    /// Characters of the answer's text received so far.
    pub characters: usize,
    /// Pieces (streamed deltas; about one token each on most servers) received so far.
    pub pieces: usize,
    /// Time since the request was sent.
    pub elapsed: Duration,
}

/// A listener of [`AnswerProgress`] reports.
pub type AnswerListener = Box<dyn FnMut(&AnswerProgress)>;

thread_local! {
    /// The listeners installed on this thread, innermost last.
    static LISTENERS: RefCell<Vec<AnswerListener>> = const { RefCell::new(Vec::new()) };
}

/// Runs `work` with `listener` hearing every [`report_answer_progress`] made on this thread
/// meanwhile (the innermost listener only, when calls nest); `None` runs it unchanged.
///
/// ```
/// use std::{cell::Cell, rc::Rc};
/// use scenethesis_models::{report_answer_progress, with_answer_listener, AnswerProgress};
/// let heard = Rc::new(Cell::new(0));
/// let seen = Rc::clone(&heard);
/// with_answer_listener(Some(Box::new(move |p: &AnswerProgress| seen.set(p.characters))), || {
///     report_answer_progress(&AnswerProgress { characters: 42, ..AnswerProgress::default() })
/// });
/// assert_eq!(heard.get(), 42);
/// report_answer_progress(&AnswerProgress::default()); // nobody listens: nothing happens
/// ```
pub fn with_answer_listener<R>(listener: Option<AnswerListener>, work: impl FnOnce() -> R) -> R {
    let Some(listener) = listener else {
        return work();
    };
    struct Installed;
    impl Drop for Installed {
        fn drop(&mut self) {
            LISTENERS.with_borrow_mut(|l| {
                l.pop();
            });
        }
    }
    LISTENERS.with_borrow_mut(|l| l.push(listener));
    let _installed = Installed;
    work()
}

/// Tells this thread's innermost listener how much of an answer has arrived (nothing when no
/// listener is installed, or when called from inside a listener).
pub fn report_answer_progress(progress: &AnswerProgress) {
    LISTENERS.with(|l| {
        if let Ok(mut listeners) = l.try_borrow_mut() {
            if let Some(listener) = listeners.last_mut() {
                listener(progress);
            }
        }
    });
}
