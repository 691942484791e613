//! Data parallelism without a dependency: natively, work is split into one chunk per core with
//! scoped threads; in wasm (one thread) it runs in place.

/// How many threads work shares: the cores natively, one in wasm.
pub fn threads() -> usize {
    if cfg!(target_arch = "wasm32") {
        1
    } else {
        std::thread::available_parallelism().map_or(1, |n| n.get()).clamp(1, 8)
    }
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
