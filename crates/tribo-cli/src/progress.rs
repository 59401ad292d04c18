//! Progress on stderr: [`tribo_case::Progress`] drawn with indicatif (a spinner per stage, a
//! bar for counted stages; hidden with `--quiet` or when stderr is not a terminal) and the
//! notes of a run as `note: ...` lines.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::time::Duration;

/// The command line's progress display.
#[derive(Debug, Default)]
pub struct Bars {
    /// Nothing on stderr, notes included (`--quiet`).
    quiet: bool,
    /// The bar of the current stage.
    bar: Option<ProgressBar>,
}

impl Bars {
    /// A display; `quiet` shows nothing.
    pub fn new(quiet: bool) -> Self {
        Bars { quiet, bar: None }
    }
}

impl tribo_case::Progress for Bars {
    fn stage(&mut self, name: &str, total: Option<u64>) {
        self.finish();
        if self.quiet {
            return;
        }
        let pb = ProgressBar::with_draw_target(total, ProgressDrawTarget::stderr());
        let template = match total {
            Some(_) => "{spinner} {msg} [{bar:30}] {pos}/{len} [{elapsed}]",
            None => "{spinner} {msg} [{elapsed}]",
        };
        if let Ok(style) = ProgressStyle::with_template(template) {
            pb.set_style(style.progress_chars("=> "));
        }
        pb.set_message(name.to_string());
        pb.enable_steady_tick(Duration::from_millis(100));
        self.bar = Some(pb);
    }

    fn status(&mut self, text: &str) {
        if let Some(pb) = &self.bar {
            pb.set_message(text.to_string());
        }
    }

    fn advance(&mut self, done: u64) {
        if let Some(pb) = &self.bar {
            pb.set_position(done);
        }
    }

    fn finish(&mut self) {
        if let Some(pb) = self.bar.take() {
            pb.finish_and_clear();
        }
    }

    fn note(&mut self, text: &str) {
        if self.quiet {
            return;
        }
        let line = format!("note: {text}");
        match &self.bar {
            Some(pb) => pb.suspend(|| crate::term::note(&line)),
            None => crate::term::note(&line),
        }
    }
}

impl Drop for Bars {
    fn drop(&mut self) {
        tribo_case::Progress::finish(self);
    }
}
