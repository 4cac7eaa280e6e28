//! Stopping a long evaluation from outside, between batches of trials.
//!
//! A caller that can be interrupted (the Python package on Ctrl-C) runs the evaluation
//! inside [`stoppable`] with a flag that another thread may raise; [`monte_carlo`]
//! (fn@crate::monte_carlo) looks at it before each batch of trials (10⁴ or more, a few
//! milliseconds) and returns [`UncertaintyError::Stopped`](crate::UncertaintyError::Stopped).
//! The flag belongs to the calling thread (the batches are started from it), so two
//! evaluations on two threads are stopped apart. Outside [`stoppable`] nothing stops.

use std::cell::RefCell;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

thread_local! {
    static FLAG: RefCell<Option<Arc<AtomicBool>>> = const { RefCell::new(None) };
}

/// Runs `f` on this thread with `flag` as its stop request: once `flag` is `true`, the
/// Monte Carlo evaluations `f` runs return `Stopped` at their next batch. The previous flag
/// (of an enclosing call) is restored after.
pub fn stoppable<R>(flag: &Arc<AtomicBool>, f: impl FnOnce() -> R) -> R {
    struct Restore(Option<Arc<AtomicBool>>);
    impl Drop for Restore {
        fn drop(&mut self) {
            let previous = self.0.take();
            FLAG.with(|f| *f.borrow_mut() = previous);
        }
    }
    let _restore = Restore(FLAG.with(|f| f.borrow_mut().replace(Arc::clone(flag))));
    f()
}

/// Whether this thread's evaluation has been asked to stop.
pub(crate) fn stop_requested() -> bool {
    FLAG.with(|f| {
        f.borrow()
            .as_ref()
            .is_some_and(|flag| flag.load(Ordering::Relaxed))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_flag_is_the_calling_threads_and_restored_after() {
        assert!(!stop_requested());
        let raised = Arc::new(AtomicBool::new(true));
        let lowered = Arc::new(AtomicBool::new(false));
        stoppable(&raised, || {
            assert!(stop_requested());
            stoppable(&lowered, || assert!(!stop_requested()));
            assert!(stop_requested());
            // another thread has no flag
            std::thread::scope(|s| {
                s.spawn(|| assert!(!stop_requested()));
            });
        });
        assert!(!stop_requested());
    }

    #[test]
    fn a_raised_flag_stops_the_monte_carlo_method_before_its_next_batch() {
        use crate::{InputQuantity, Inputs, McOptions, Trials, UncertaintyError, model_fn};
        let inputs = Inputs::new(vec![InputQuantity::normal("x", 1.0, 0.1)]).unwrap();
        let model = model_fn(["y"], |x, y| {
            y[0] = 2.0 * x[0];
            Ok(())
        });
        let options = McOptions {
            trials: Trials::Fixed(1_000_000),
            ..McOptions::default()
        };
        let raised = Arc::new(AtomicBool::new(true));
        let stopped = stoppable(&raised, || crate::monte_carlo(&model, &inputs, &options));
        assert_eq!(
            stopped.unwrap_err(),
            UncertaintyError::Stopped { trials: 0 }
        );
        // not raised: the same evaluation runs to its end
        let lowered = Arc::new(AtomicBool::new(false));
        let done = stoppable(&lowered, || crate::monte_carlo(&model, &inputs, &options)).unwrap();
        assert_eq!(done.trials, 1_000_000);
    }
}
