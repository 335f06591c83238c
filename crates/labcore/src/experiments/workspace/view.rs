//! What experiment 3 shows: the view box, the scene, the readouts and the status.

use super::*;

impl Presentation for Workspace {
    /// The arm's current reach fills the canvas.
    fn view(&self) -> ViewBox {
        ViewBox::framing(self.lengths_m.iter().sum::<f64>())
    }

    fn scene(&self, out: &mut Scene) {
        out.axes(self.view());
        if !self.tips.is_empty() {
            out.push(Item::Heatmap {
                min: self.density.min,
                cell_m: self.density.cell_m,
                cols: self.density.cols,
                rows: self.density.rows,
                values: self.density.normalized(),
                role: Role::Sample,
            });
            let from = self.tips.len().saturating_sub(STIPPLE_MAX);
            out.push(Item::Points {
                points: self.tips[from..].to_vec(),
                radius_px: 0.9,
                role: Role::Sample,
            });
        }
        let annulus = Annulus::of_chain(&self.lengths_m);
        out.bound_circle(annulus.outer_m);
        out.bound_circle(annulus.inner_m);
        let pose = forward(&self.lengths_m, &self.angles_rad());
        out.chain(&pose.points, Role::Link);
    }

    fn readouts(&self) -> Vec<Readout> {
        let tip = self.tip();
        let annulus = Annulus::of_chain(&self.lengths_m);
        let measured = self.sampler.as_ref().and_then(WorkspaceSampler::measured);
        // The same 3 decimals (1 mm) as every length readout: with the
        // default 20,000 samples the measured radii stay a few mm inside theory.
        let metres = crate::units::format_metres;
        let (outer, inner) = measured.map_or(("--".into(), "--".into()), |m| {
            (metres(m.outer_m), metres(m.inner_m))
        });
        vec![
            Readout::new("x", "Tip X", metres(tip.x)),
            Readout::new("y", "Tip Y", metres(tip.y)),
            Readout::new("outer", "Outer radius (measured)", outer),
            Readout::new(
                "outer_theory",
                "Outer radius (theory)",
                metres(annulus.outer_m),
            ),
            Readout::new("inner", "Inner hole (measured)", inner),
            Readout::new(
                "inner_theory",
                "Inner hole (theory)",
                metres(annulus.inner_m),
            ),
            Readout::new(
                "samples",
                "Samples drawn",
                self.sampler
                    .as_ref()
                    .map_or("0".into(), |s| match s.mode() {
                        SamplingMode::Grid { per_joint } if s.total() != self.samples => format!(
                            "{} / {} ({per_joint}³ grid of {} requested)",
                            s.produced(),
                            s.total(),
                            self.samples
                        ),
                        _ => format!("{} / {}", s.produced(), s.total()),
                    }),
            ),
        ]
    }

    fn status(&self) -> Status {
        match &self.sampler {
            None => Status::new("ready to sweep", Tone::Neutral),
            // Whole percents, current with the cloud (the page decides how
            // often its live region announces them).
            Some(s) if !s.is_done() => Status::new(
                format!(
                    "sweeping… {}%{}",
                    // Integer arithmetic: 0.29 × 100 would floor to 28.
                    s.produced().saturating_mul(100) / s.total().max(1),
                    self.grid_note()
                        .map_or(String::new(), |n| format!(" ({n})"))
                ),
                Tone::Neutral,
            ),
            Some(s) => Status::ended(
                match self.grid_note() {
                    None => format!("swept {} samples", s.produced()),
                    Some(note) => format!("swept {} samples ({note})", s.produced()),
                },
                Tone::Good,
            ),
        }
    }

    fn notice(&self) -> Option<Notice> {
        self.notices.current()
    }

    /// "Tip at (1.17, 2.02) m. Swept 8000 samples: outer radius 2.500 m (theory 2.500 m), …"
    fn describe(&self) -> String {
        let value = |key| crate::experiment::readout_value(self, key).unwrap_or_default();
        let tip = format!(
            "{}-link arm, tip at {}",
            self.lengths_m.len(),
            format_point(self.tip())
        );
        if self.tips.is_empty() {
            format!(
                "{tip}. No workspace sweep yet: press Sweep workspace; {}.",
                self.status().text
            )
        } else {
            format!(
                "{tip}. {}: {} samples; outer radius {} measured, {} in theory; inner hole {} measured, {} in theory.",
                self.status().text,
                value("samples"),
                value("outer"),
                value("outer_theory"),
                value("inner"),
                value("inner_theory")
            )
        }
    }

    fn hint(&self) -> &'static str {
        "Press Sweep workspace to sample joint space; drag the tip or use the sliders to pose the arm."
    }

    fn preview(&mut self) {
        self.samples = 8000;
        self.start_sweep();
        while self.sweeping() {
            self.step(1.0 / 60.0);
        }
    }
}
