//! The shell's simulation clock: play, pause, single step, speed, all on a
//! fixed step so a run is the same however the frames fall.
//!
//! Real time goes in ([`Clock::advance`]), a whole number of fixed steps comes
//! out; the experiment only ever sees [`Clock::DT_S`]. Running N steps and
//! pressing "step" N times from a pause give the same state because both call
//! [`crate::Experiment::step`] N times with the same `dt`.

/// Playback speeds offered by the time controls (simulated s per real s).
pub const SPEEDS: [f64; 5] = [0.25, 0.5, 1.0, 2.0, 4.0];

/// Fixed-step accumulator with play/pause and a speed factor.
#[derive(Clone, Debug, PartialEq)]
pub struct Clock {
    running: bool,
    speed: f64,
    accumulator_s: f64,
    /// Steps taken since the last reset.
    steps: u64,
}

impl Default for Clock {
    fn default() -> Self {
        Self {
            running: true,
            speed: 1.0,
            accumulator_s: 0.0,
            steps: 0,
        }
    }
}

impl Clock {
    /// The fixed simulation step, seconds.
    pub const DT_S: f64 = 1.0 / 60.0;
    /// At most this many steps per call of [`Clock::advance`]: after a stall
    /// the simulation slows down instead of freezing the page to catch up.
    pub const MAX_STEPS_PER_FRAME: u32 = 16;

    #[must_use]
    pub fn running(&self) -> bool {
        self.running
    }

    /// Plays or pauses; pausing drops any partial step.
    pub fn set_running(&mut self, running: bool) {
        self.running = running;
        self.accumulator_s = 0.0;
    }

    #[must_use]
    pub fn speed(&self) -> f64 {
        self.speed
    }

    /// Sets the speed to the nearest of [`SPEEDS`]; NaN keeps the current one.
    /// Returns the speed applied.
    pub fn set_speed(&mut self, speed: f64) -> f64 {
        if speed.is_finite() {
            self.speed = nearest_speed(speed);
        }
        self.speed
    }

    /// Simulated time since the last reset, seconds.
    #[must_use]
    pub fn time_s(&self) -> f64 {
        self.steps as f64 * Self::DT_S
    }

    #[must_use]
    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// Puts the clock at step `steps` of the run (the timeline went there,
    /// or a replay of the record moved on); the running state, the speed
    /// and any partial step are kept.
    pub fn seek(&mut self, steps: u64) {
        self.steps = steps;
    }

    /// Back to t = 0 (the running state and speed are kept).
    pub fn reset(&mut self) {
        self.accumulator_s = 0.0;
        self.steps = 0;
    }

    /// How many fixed steps to take for `elapsed_s` of real time (0 while
    /// paused, or for a NaN, negative or infinite interval). Counts them.
    pub fn advance(&mut self, elapsed_s: f64) -> u32 {
        if !self.running || !elapsed_s.is_finite() || elapsed_s <= 0.0 {
            return 0;
        }
        // A long gap (a background tab, a debugger) is not caught up.
        self.accumulator_s += elapsed_s.min(0.25) * self.speed;
        let mut n = 0;
        while self.accumulator_s >= Self::DT_S && n < Self::MAX_STEPS_PER_FRAME {
            self.accumulator_s -= Self::DT_S;
            n += 1;
        }
        if n == Self::MAX_STEPS_PER_FRAME {
            self.accumulator_s = 0.0;
        }
        self.steps += u64::from(n);
        n
    }

    /// Takes the `steps` that [`Clock::advance`] gave, calling `step` for
    /// each, but stops once `spent_ms()` (the frame's work so far) reaches
    /// `budget_ms`, or once `step` returns `false` (the run ended: a step
    /// after the end would count time the run never had); the first step is
    /// always taken. The steps not taken are not counted: after a slow frame
    /// the simulation runs slower than real time for a moment instead of
    /// piling the catch-up into one long frame (which would make the next
    /// frame slower still). Returns the steps taken.
    ///
    /// Which steps run never depends on time, only how many fall in a frame:
    /// step N of a run is the same state however the frames fell, and a run
    /// ends at the same step however they fell.
    pub fn take_steps(
        &mut self,
        steps: u32,
        budget_ms: f64,
        mut spent_ms: impl FnMut() -> f64,
        mut step: impl FnMut() -> bool,
    ) -> u32 {
        let mut taken = 0;
        while taken < steps {
            let goes_on = step();
            taken += 1;
            if !goes_on || spent_ms() >= budget_ms {
                break;
            }
        }
        self.steps -= u64::from(steps - taken);
        taken
    }

    /// One press of the Step button: pauses, then takes `steps` fixed steps
    /// (the model's own step, [`Clock::fixed_steps_in`]), calling `step` for
    /// each until it returns `false` (the run ended). Counts and returns the
    /// steps taken.
    pub fn single_step(&mut self, steps: u32, mut step: impl FnMut() -> bool) -> u32 {
        self.set_running(false);
        let mut taken = 0;
        while taken < steps {
            taken += 1;
            if !step() {
                break;
            }
        }
        self.steps += u64::from(taken);
        taken
    }

    /// How many fixed steps of [`Clock::DT_S`] make a model step of
    /// `step_s` seconds ([`crate::Experiment::natural_step_s`]): the nearest
    /// whole number, at least 1 (1 for a NaN or infinite step).
    #[must_use]
    pub fn fixed_steps_in(step_s: f64) -> u32 {
        let n = (step_s / Self::DT_S).round();
        if n.is_finite() && n >= 1.0 {
            n.min(f64::from(u32::MAX)) as u32
        } else {
            1
        }
    }
}

/// The entry of [`SPEEDS`] closest to `speed` (in ratio).
#[must_use]
pub fn nearest_speed(speed: f64) -> f64 {
    let target = crate::math::ln(speed.max(1e-9));
    SPEEDS
        .iter()
        .copied()
        .min_by(|a, b| {
            (crate::math::ln(*a) - target)
                .abs()
                .total_cmp(&(crate::math::ln(*b) - target).abs())
        })
        .unwrap_or(1.0)
}

/// Whether `dt_s` is a step an experiment accepts: finite, positive and at
/// most [`MAX_DT_S`]. Every [`crate::Experiment::step`] refuses anything else
/// and leaves its state as it was.
#[must_use]
pub fn valid_dt(dt_s: f64) -> bool {
    dt_s.is_finite() && dt_s > 0.0 && dt_s <= MAX_DT_S
}

/// The longest step any experiment accepts, seconds.
pub const MAX_DT_S: f64 = 0.1;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fixed_steps_from_real_time() {
        let mut c = Clock::default();
        assert_eq!(c.advance(0.5 / 60.0), 0);
        assert_eq!(c.advance(0.6 / 60.0), 1);
        assert_eq!(c.advance(2.0 / 60.0), 2);
        c.set_speed(2.0);
        assert_eq!(c.advance(1.0 / 60.0), 2);
        c.set_speed(0.25);
        assert_eq!(c.advance(2.0 / 60.0), 0);
        assert_eq!(c.advance(2.0 / 60.0), 1);
        assert_eq!(c.steps(), 6);
    }

    #[test]
    fn paused_clock_and_bad_intervals_take_no_steps() {
        let mut c = Clock::default();
        c.set_running(false);
        assert_eq!(c.advance(1.0), 0);
        c.set_running(true);
        for bad in [f64::NAN, f64::INFINITY, -1.0, 0.0] {
            assert_eq!(c.advance(bad), 0);
        }
        // A stall is capped, not caught up: at most a quarter second of
        // real time counts, and at most MAX_STEPS_PER_FRAME steps.
        assert!((14..=15).contains(&c.advance(10.0)));
        c.set_speed(4.0);
        assert_eq!(c.advance(10.0), Clock::MAX_STEPS_PER_FRAME);
    }

    #[test]
    fn a_frame_over_its_work_budget_stops_stepping_and_uncounts_the_rest() {
        let mut c = Clock::default();
        let given = c.advance(0.25);
        assert_eq!(given, 15);
        // Each step costs 3 ms of a 10 ms budget: the fourth crosses it.
        let spent = std::cell::Cell::new(0.0);
        let mut ran = 0;
        let taken = c.take_steps(
            given,
            10.0,
            || spent.get(),
            || {
                spent.set(spent.get() + 3.0);
                ran += 1;
                true
            },
        );
        assert_eq!((taken, ran), (4, 4));
        assert_eq!(c.steps(), 4, "the 11 steps not taken are not counted");
        // A single step over the whole budget is still taken.
        let given = c.advance(2.5 / 60.0);
        assert_eq!(given, 2);
        assert_eq!(c.take_steps(given, 1.0, || 50.0, || true), 1);
        assert_eq!(c.steps(), 5);
        // Within budget, every step given is taken.
        let given = c.advance(3.2 / 60.0);
        assert_eq!(given, 3);
        assert_eq!(c.take_steps(given, 10.0, || 0.0, || true), 3);
        assert_eq!(c.steps(), 8);
    }

    #[test]
    fn speed_snaps_to_offered_values() {
        let mut c = Clock::default();
        assert_eq!(c.set_speed(3.0), 4.0);
        assert_eq!(c.set_speed(0.3), 0.25);
        assert_eq!(c.set_speed(f64::NAN), 0.25);
        assert_eq!(c.set_speed(1e300), 4.0);
        assert_eq!(c.set_speed(-5.0), 0.25);
    }

    #[test]
    fn a_frame_stops_stepping_when_the_run_ends_and_counts_only_the_steps_taken() {
        let mut c = Clock::default();
        let given = c.advance(5.5 / 60.0);
        assert_eq!(given, 5);
        // The run ends on its second step: the three after it never happen.
        let mut left = 2;
        let taken = c.take_steps(
            given,
            100.0,
            || 0.0,
            || {
                left -= 1;
                left > 0
            },
        );
        assert_eq!(taken, 2);
        assert_eq!(c.steps(), 2);
    }

    #[test]
    fn a_step_press_takes_the_models_step_in_fixed_steps() {
        assert_eq!(Clock::fixed_steps_in(Clock::DT_S), 1);
        assert_eq!(Clock::fixed_steps_in(0.05), 3);
        assert_eq!(Clock::fixed_steps_in(0.02), 1);
        for odd in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            assert_eq!(Clock::fixed_steps_in(odd), 1, "{odd}");
        }
        let mut c = Clock::default();
        let mut ran = 0;
        assert_eq!(
            c.single_step(3, || {
                ran += 1;
                true
            }),
            3
        );
        assert_eq!((ran, c.steps(), c.running()), (3, 3, false));
        // A press that ends the run stops there.
        assert_eq!(c.single_step(3, || false), 1);
        assert_eq!(c.steps(), 4);
    }

    #[test]
    fn single_step_pauses_and_counts() {
        let mut c = Clock::default();
        assert_eq!(c.single_step(1, || true), 1);
        assert!(!c.running());
        assert_eq!(c.steps(), 1);
        assert!((c.time_s() - Clock::DT_S).abs() < 1e-15);
        c.reset();
        assert_eq!(c.steps(), 0);
    }

    #[test]
    fn dt_contract() {
        assert!(valid_dt(Clock::DT_S));
        assert!(valid_dt(MAX_DT_S));
        for bad in [0.0, -0.01, f64::NAN, f64::INFINITY, 0.2] {
            assert!(!valid_dt(bad), "{bad}");
        }
    }
}
