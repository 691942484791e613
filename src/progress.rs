//! Progress reporting and cancellation for long work. A job reports fractions in [0, 1]; the
//! sink (the CLI's bar, the page's worker) returns `false` to cancel, and the work then stops at
//! its next report with [`crate::Error::Cancelled`].

/// A progress sink scaled to a sub-range of the whole job.
pub struct Progress<'a> {
    sink: Option<&'a mut dyn FnMut(f64, &str) -> bool>,
    start: f64,
    span: f64,
    stage: String,
    /// The part of the whole that stages are fractions of, and the name they are prefixed
    /// with (an operation's own progress within a job).
    frame: (f64, f64),
    prefix: Option<String>,
    /// The frame [`Progress::enter`] left, while its stage is the frame.
    entered: Option<(f64, f64)>,
    /// The furthest point reported in the frame: a stage that would move the bar back (work
    /// whose flow is not known ahead, as the octree roughing's stages) holds it there instead.
    furthest: f64,
    /// How many reports were held so.
    held: usize,
    cancelled: bool,
}

impl<'a> Progress<'a> {
    /// Reports to `sink`, which returns `false` to cancel.
    pub fn new(sink: &'a mut dyn FnMut(f64, &str) -> bool) -> Progress<'a> {
        Progress { sink: Some(sink), start: 0.0, span: 1.0, stage: String::new(), frame: (0.0, 1.0), prefix: None, entered: None, furthest: f64::NEG_INFINITY, held: 0, cancelled: false }
    }

    /// Reports nowhere and never cancels.
    pub fn none() -> Progress<'static> {
        Progress { sink: None, start: 0.0, span: 1.0, stage: String::new(), frame: (0.0, 1.0), prefix: None, entered: None, furthest: f64::NEG_INFINITY, held: 0, cancelled: false }
    }

    /// Enters the stage `name`, which covers `[start, start + span]` of the frame (the whole,
    /// unless [`Progress::frame`] set one).
    pub fn stage(&mut self, name: &str, start: f64, span: f64) -> bool {
        self.stage = match &self.prefix {
            Some(p) => format!("{p}: {name}"),
            None => name.to_owned(),
        };
        self.start = self.frame.0 + self.frame.1 * start;
        self.span = self.frame.1 * span;
        self.report(0.0)
    }

    /// Makes `[start, start + span]` of the whole the frame later stages are fractions of, their
    /// names prefixed by `prefix` (one operation of a job); `frame(0, 1, None)` ends it.
    pub fn frame(&mut self, start: f64, span: f64, prefix: Option<&str>) {
        self.entered = None;
        self.furthest = f64::NEG_INFINITY;
        self.frame = (start, span);
        self.prefix = prefix.map(str::to_owned);
    }

    /// Enters the stage `name` as [`Progress::stage`] does, and makes it the frame of the
    /// stages that follow (work of its own that names stages in `[0, 1]`), until the next
    /// `enter`, which is again a stage of the frame before, or [`Progress::leave`]: nested
    /// stages then move the bar forward within this one, never back to the operation's start.
    pub fn enter(&mut self, name: &str, start: f64, span: f64) -> bool {
        self.leave();
        self.entered = Some(self.frame);
        let going = self.stage(name, start, span);
        self.frame = (self.start, self.span);
        going
    }

    /// How many reports would have moved the bar back within an operation, and were held.
    pub fn held(&self) -> usize {
        self.held
    }

    /// Ends what [`Progress::enter`] began.
    pub fn leave(&mut self) {
        if let Some(outer) = self.entered.take() {
            self.frame = outer;
        }
    }

    /// Reports `fraction` of the current stage; `false` means the user cancelled.
    pub fn report(&mut self, fraction: f64) -> bool {
        if self.cancelled {
            return false;
        }
        if let Some(sink) = self.sink.as_mut() {
            let mut whole = self.start + self.span * fraction.clamp(0.0, 1.0);
            if whole < self.furthest - 1e-9 {
                self.held += 1;
                whole = self.furthest;
            }
            self.furthest = whole;
            if !sink(whole, &self.stage) {
                self.cancelled = true;
            }
        }
        !self.cancelled
    }

    /// Runs `work` with a progress of its own whose whole is `[start, start + span]` of this
    /// one's, its stages named after `name` (one setup of several, each a whole job):
    /// cancelling it cancels this one.
    pub fn within<R>(&mut self, start: f64, span: f64, name: &str, work: impl FnOnce(&mut Progress) -> R) -> R {
        let Some(outer) = self.sink.as_mut() else { return work(&mut Progress::none()) };
        let mut cancelled = false;
        let mut sink = |f: f64, stage: &str| {
            let ok = outer(start + span * f, &format!("{name}: {stage}"));
            cancelled |= !ok;
            ok
        };
        let out = work(&mut Progress::new(&mut sink));
        self.cancelled |= cancelled;
        out
    }
}
