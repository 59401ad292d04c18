//! Progress of a run, as an observer: the pipeline tells it the stages it enters, how far a
//! counted stage is, and notes for the user (a coarse height map, a dangerous region at the
//! edge of the field box, ...). It never prints itself; a front end decides what to show.

/// An observer of a running case. Every method has an empty default, so an implementation
/// overrides only what it shows.
pub trait Progress {
    /// A stage begins: `name` says what is computed, `total` the count of its steps where it
    /// has one (curve points, field depths). Ends the previous stage.
    fn stage(&mut self, name: &str, total: Option<u64>) {
        let _ = (name, total);
    }
    /// A new status line within the stage (a solver's iteration and residual).
    fn status(&mut self, text: &str) {
        let _ = text;
    }
    /// `done` of the stage's `total` steps are done.
    fn advance(&mut self, done: u64) {
        let _ = done;
    }
    /// The current stage ended.
    fn finish(&mut self) {}
    /// A note for the user about the case or its results (a line of text, no prefix).
    fn note(&mut self, text: &str) {
        let _ = text;
    }
}

/// A [`Progress`] that shows nothing.
#[derive(Debug, Default, Clone, Copy)]
pub struct Silent;

impl Progress for Silent {}

/// A [`Progress`] that writes one line per stage and per note into a [`std::fmt::Write`] (a
/// `String`, say): for logs and non-terminals, where a moving bar has no place. Status lines
/// and step counts are not written.
#[derive(Debug, Default)]
pub struct Lines<W> {
    /// Where the lines go.
    pub out: W,
}

impl<W: std::fmt::Write> Progress for Lines<W> {
    fn stage(&mut self, name: &str, total: Option<u64>) {
        let _ = match total {
            Some(n) => writeln!(self.out, "{name} ({n} steps)"),
            None => writeln!(self.out, "{name}"),
        };
    }
    fn note(&mut self, text: &str) {
        let _ = writeln!(self.out, "note: {text}");
    }
}

/// Forwards the stages of an inner run to another [`Progress`] but drops its notes (the
/// inner run of the limiting state repeats the notes of the case itself).
pub struct WithoutNotes<'a>(pub &'a mut dyn Progress);

impl Progress for WithoutNotes<'_> {
    fn stage(&mut self, name: &str, total: Option<u64>) {
        self.0.stage(name, total);
    }
    fn status(&mut self, text: &str) {
        self.0.status(text);
    }
    fn advance(&mut self, done: u64) {
        self.0.advance(done);
    }
    fn finish(&mut self) {
        self.0.finish();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_write_stages_and_notes_only() {
        let mut p = Lines::<String>::default();
        p.stage("normal contact", None);
        p.status("iteration 3");
        p.advance(2);
        p.stage("stress field", Some(20));
        p.note("coarse map");
        p.finish();
        assert_eq!(
            p.out,
            "normal contact\nstress field (20 steps)\nnote: coarse map\n"
        );
    }

    #[test]
    fn without_notes_drops_notes_only() {
        let mut inner = Lines::<String>::default();
        let mut p = WithoutNotes(&mut inner);
        p.stage("limiting state", None);
        p.note("dropped");
        assert_eq!(inner.out, "limiting state\n");
    }
}
