//! Data parallelism without a dependency: natively, work is split into one chunk per core with
//! scoped threads; in wasm (one thread) it runs in place.

/// How many threads work shares: the cores natively, one in wasm (and within [`alone`]).
pub fn threads() -> usize {
    if cfg!(target_arch = "wasm32") || ALONE.get() {
        1
    } else {
        std::thread::available_parallelism().map_or(1, |n| n.get()).clamp(1, 8)
    }
}

thread_local! {
    static ALONE: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// `f` with all its work on this thread, as the page's engine does it in wasm: for checking
/// that the cores change nothing but the time (with one thread no other is started, so the
/// setting holds wherever the work goes).
pub fn alone<R>(f: impl FnOnce() -> R) -> R {
    let before = ALONE.replace(true);
    let out = f();
    ALONE.set(before);
    out
}

/// `(0..count).map(f)`, in order, on every core.
pub fn map<U: Send>(count: usize, f: impl Fn(usize) -> U + Sync) -> Vec<U> {
    map_from(count, 1024, f)
}

/// [`map`] for items that each take long (a raster pass): split from two items on.
pub fn map_heavy<U: Send>(count: usize, f: impl Fn(usize) -> U + Sync) -> Vec<U> {
    map_from(count, 2, f)
}

fn map_from<U: Send>(count: usize, least: usize, f: impl Fn(usize) -> U + Sync) -> Vec<U> {
    let threads = threads().min(count.max(1));
    if threads <= 1 || count < least {
        return (0..count).map(f).collect();
    }
    let chunk = count.div_ceil(threads);
    let f = &f;
    let parts: Vec<Vec<U>> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..threads).map(|t| scope.spawn(move || (t * chunk..((t + 1) * chunk).min(count)).map(f).collect::<Vec<U>>())).collect();
        handles.into_iter().map(|h| h.join().expect("a worker thread panicked")).collect()
    });
    parts.into_iter().flatten().collect()
}

/// `(0..count).map(f)`, in order, each item on whichever core is free next (items of uneven
/// work, such as regions of different sizes); in place in wasm.
pub fn map_uneven<U: Send>(count: usize, f: impl Fn(usize) -> U + Sync) -> Vec<U> {
    let mut slots: Vec<(usize, Option<U>)> = (0..count).map(|k| (k, None)).collect();
    each_mut(&mut slots, |(k, out)| *out = Some(f(*k)));
    slots.into_iter().map(|(_, made)| made.expect("every item is made")).collect()
}

/// `f` on every item, each on whichever core is free next (for items of uneven work); in place,
/// in order, in wasm.
pub fn each_mut<T: Send>(items: &mut [T], f: impl Fn(&mut T) + Sync) {
    let threads = threads().min(items.len());
    if threads <= 1 {
        items.iter_mut().for_each(f);
        return;
    }
    let next = std::sync::atomic::AtomicUsize::new(0);
    let slots: Vec<std::sync::Mutex<&mut T>> = items.iter_mut().map(std::sync::Mutex::new).collect();
    let (f, next, slots) = (&f, &next, &slots);
    std::thread::scope(|scope| {
        for _ in 0..threads {
            scope.spawn(move || loop {
                let k = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                let Some(slot) = slots.get(k) else { break };
                f(&mut slot.lock().expect("each item is taken once"));
            });
        }
    });
}

/// Runs `main` on this thread while a second one makes `make(k)` for every `k` of `0..count`
/// ahead of it, in order; `main` takes item `k` (each at most once, in any order) by the
/// function it is given: the item made ahead, else made there and then (one the second thread
/// is making is waited for). The same items either way; in wasm (one thread) each is made when
/// taken.
pub fn ahead<T: Send, R>(count: usize, make: impl Fn(usize) -> T + Sync, main: impl FnOnce(&dyn Fn(usize) -> T) -> R) -> R {
    if threads() <= 1 || count == 0 {
        return main(&make);
    }
    enum Slot<T> {
        Waiting,
        Made(T),
        Taken,
    }
    use std::sync::atomic::{AtomicBool, Ordering};
    use std::sync::Mutex;
    let slots: Vec<Mutex<Slot<T>>> = (0..count).map(|_| Mutex::new(Slot::Waiting)).collect();
    let finished = AtomicBool::new(false);
    let (make, slots, finished) = (&make, &slots, &finished);
    std::thread::scope(|scope| {
        scope.spawn(move || {
            for (k, slot) in slots.iter().enumerate() {
                if finished.load(Ordering::Relaxed) {
                    break;
                }
                // One `main` holds is being made there: on to the next.
                if let Ok(mut slot) = slot.try_lock() {
                    if matches!(*slot, Slot::Waiting) {
                        *slot = Slot::Made(make(k));
                    }
                }
            }
        });
        let take = move |k: usize| {
            let mut slot = slots[k].lock().expect("a slot is never left half made");
            match std::mem::replace(&mut *slot, Slot::Taken) {
                Slot::Made(item) => item,
                Slot::Waiting => make(k),
                Slot::Taken => panic!("item {k} taken twice"),
            }
        };
        let out = main(&take);
        finished.store(true, Ordering::Relaxed);
        out
    })
}

/// Runs `main` on this thread, which hands jobs to the function it is given, while a second
/// thread works them by `work` in the order handed; returns `main`'s result and the jobs'
/// results in that order. In wasm (one thread) each job is worked when handed.
pub fn behind<J: Send, U: Send, R>(work: impl Fn(J) -> U + Sync, main: impl FnOnce(&mut dyn FnMut(J)) -> R) -> (R, Vec<U>) {
    if threads() <= 1 {
        let mut done = Vec::new();
        let out = main(&mut |job| done.push(work(job)));
        return (out, done);
    }
    let (send, jobs) = std::sync::mpsc::channel::<J>();
    let work = &work;
    std::thread::scope(|scope| {
        let worker = scope.spawn(move || jobs.into_iter().map(work).collect::<Vec<U>>());
        let out = main(&mut |job| send.send(job).expect("the worker takes jobs until main is done"));
        drop(send);
        (out, worker.join().expect("the worker thread panicked"))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uneven_items_come_back_in_order() {
        // Work growing with the item (as later pieces try more pieces before them).
        let got = map_uneven(300, |k| (0..k * 50).fold(k as u64, |a, j| a.wrapping_mul(31).wrapping_add(j as u64)));
        let want: Vec<u64> = (0..300).map(|k| (0..k * 50).fold(k as u64, |a, j| a.wrapping_mul(31).wrapping_add(j as u64))).collect();
        assert_eq!(got, want);
        assert!(map_uneven(0, |k| k).is_empty());
    }

    #[test]
    fn items_made_ahead_are_the_items_asked_for_in_any_order() {
        // Taken in an order of their own, some at once (before the second thread reaches them),
        // some late: each is the one asked for, made once.
        let made = std::sync::atomic::AtomicUsize::new(0);
        let order: Vec<usize> = (0..200).map(|k| (k * 37) % 200).collect();
        let got = ahead(
            200,
            |k| {
                made.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                k * k
            },
            |take| order.iter().map(|&k| take(k)).collect::<Vec<_>>(),
        );
        assert_eq!(got, order.iter().map(|k| k * k).collect::<Vec<_>>());
        assert_eq!(made.load(std::sync::atomic::Ordering::Relaxed), 200);
        // Main may stop early: the second thread stops too, and nothing is left waiting.
        assert_eq!(ahead(1000, |k| k, |take| take(999)), 999);
    }

    #[test]
    fn jobs_worked_behind_come_back_in_the_order_handed() {
        let (sum, done) = behind(
            |j: u64| j * 3,
            |send| {
                let mut sum = 0;
                for j in (0..500).rev() {
                    send(j);
                    sum += j;
                }
                sum
            },
        );
        assert_eq!(sum, (0..500).sum::<u64>());
        assert_eq!(done, (0..500).rev().map(|j| j * 3).collect::<Vec<_>>());
    }
}
