//! A usage meter: requests, tokens and cache hits of one model, for `report.json`; and
//! [`metered`], which attributes what meters record on one thread to one run, so runs sharing
//! a provider in parallel (a batch) each report their own use.

use std::cell::RefCell;
use std::sync::{Arc, Mutex, PoisonError};

use serde::{Deserialize, Serialize};

use crate::chat::TokenUsage;

/// What a run used of one model; serialisable into a report.
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct UsageReport {
    /// The provider (an endpoint without credentials, or a provider name).
    pub provider: String,
    /// The model.
    pub model: String,
    /// Requests sent to the provider (each HTTP attempt, retries and fallbacks included).
    pub requests: u64,
    /// Calls answered from the response cache.
    pub cache_hits: u64,
    /// Retries after transient failures.
    pub retries: u64,
    /// Tokens of the requests, as reported by the provider.
    pub prompt_tokens: u64,
    /// Tokens of the answers, as reported by the provider.
    pub completion_tokens: u64,
}

/// A shared, thread-safe counter of a model's use; clones count into the same totals.
#[derive(Debug, Clone, Default)]
pub struct UsageMeter {
    inner: Arc<Mutex<UsageReport>>,
}

impl UsageMeter {
    /// A meter for `model` at `provider`, all counts zero.
    pub fn new(provider: impl Into<String>, model: impl Into<String>) -> Self {
        Self {
            inner: Arc::new(Mutex::new(UsageReport {
                provider: provider.into(),
                model: model.into(),
                ..UsageReport::default()
            })),
        }
    }

    fn update(&self, f: impl Fn(&mut UsageReport)) {
        let mut guard = self.inner.lock().unwrap_or_else(PoisonError::into_inner);
        f(&mut guard);
        RUN_SCOPES.with_borrow_mut(|scopes| {
            for scope in scopes.iter_mut() {
                let entry = match scope
                    .iter()
                    .position(|r| r.provider == guard.provider && r.model == guard.model)
                {
                    Some(i) => &mut scope[i],
                    None => {
                        scope.push(UsageReport {
                            provider: guard.provider.clone(),
                            model: guard.model.clone(),
                            ..UsageReport::default()
                        });
                        scope.last_mut().expect("just pushed")
                    }
                };
                f(entry);
            }
        });
    }

    /// Counts one request sent to the provider and the tokens it reported.
    pub fn record_request(&self, tokens: TokenUsage) {
        self.update(|r| {
            r.requests += 1;
            r.prompt_tokens += tokens.prompt_tokens;
            r.completion_tokens += tokens.completion_tokens;
        });
    }

    /// Adds tokens reported for a request already counted.
    pub fn record_tokens(&self, tokens: TokenUsage) {
        self.update(|r| {
            r.prompt_tokens += tokens.prompt_tokens;
            r.completion_tokens += tokens.completion_tokens;
        });
    }

    /// Counts one call answered from the cache.
    pub fn record_cache_hit(&self) {
        self.update(|r| r.cache_hits += 1);
    }

    /// Counts one retry.
    pub fn record_retry(&self) {
        self.update(|r| r.retries += 1);
    }

    /// The totals so far.
    pub fn snapshot(&self) -> UsageReport {
        self.inner
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .clone()
    }
}

thread_local! {
    /// The open [`metered`] scopes of this thread, innermost last.
    static RUN_SCOPES: RefCell<Vec<Vec<UsageReport>>> = const { RefCell::new(Vec::new()) };
}

/// Runs `work` and returns, beside its result, what every [`UsageMeter`] recorded on this
/// thread while it ran: one report per provider and model, in the order they were first used.
/// Meters keep their shared totals as well; scopes nest (an outer scope also counts what an
/// inner one saw). Requests made on other threads are not attributed to this scope.
///
/// ```
/// use scenethesis_models::{metered, TokenUsage, UsageMeter};
/// let meter = UsageMeter::new("http://127.0.0.1:8000/v1", "small-model");
/// meter.record_request(TokenUsage::default());
/// let ((), used) = metered(|| meter.record_cache_hit());
/// assert_eq!((used[0].requests, used[0].cache_hits), (0, 1));
/// assert_eq!(meter.snapshot().requests, 1);
/// ```
pub fn metered<R>(work: impl FnOnce() -> R) -> (R, Vec<UsageReport>) {
    struct Scope;
    impl Drop for Scope {
        fn drop(&mut self) {
            RUN_SCOPES.with_borrow_mut(|scopes| {
                scopes.pop();
            });
        }
    }
    RUN_SCOPES.with_borrow_mut(|scopes| scopes.push(Vec::new()));
    let scope = Scope;
    let result = work();
    let used = RUN_SCOPES.with_borrow_mut(|scopes| scopes.last_mut().map(std::mem::take));
    drop(scope);
    (result, used.unwrap_or_default())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clones_share_totals_across_threads() {
        let meter = UsageMeter::new("http://127.0.0.1:1/v1", "m");
        let handles: Vec<_> = (0..4)
            .map(|_| {
                let m = meter.clone();
                std::thread::spawn(move || {
                    m.record_request(TokenUsage {
                        prompt_tokens: 10,
                        completion_tokens: 2,
                    });
                    m.record_cache_hit();
                })
            })
            .collect();
        for h in handles {
            h.join().unwrap();
        }
        meter.record_retry();
        let r = meter.snapshot();
        assert_eq!(
            (
                r.requests,
                r.cache_hits,
                r.retries,
                r.prompt_tokens,
                r.completion_tokens
            ),
            (4, 4, 1, 40, 8)
        );
        assert_eq!(r.model, "m");
    }

    #[test]
    fn a_scope_sees_only_its_own_thread_and_nests() {
        let meter = UsageMeter::new("p", "m");
        let other = meter.clone();
        let ((), outer) = metered(|| {
            meter.record_request(TokenUsage::default());
            std::thread::spawn(move || other.record_request(TokenUsage::default()))
                .join()
                .unwrap();
            let ((), inner) = metered(|| meter.record_retry());
            assert_eq!(
                (inner.len(), inner[0].retries, inner[0].requests),
                (1, 1, 0)
            );
        });
        assert_eq!(outer.len(), 1);
        assert_eq!((outer[0].requests, outer[0].retries), (1, 1));
        assert_eq!(meter.snapshot().requests, 2);
        let ((), none) = metered(|| ());
        assert!(none.is_empty());
    }
}
