//! The progress bar: an indicatif bar on a terminal (hidden otherwise) moved by a library
//! [`trirhythm::monitor::Monitor`].

/// A library call's monitor that hands its progress (done, total) to a closure (which moves a
/// progress bar).
pub struct Report<F>(pub F);

impl<T: ?Sized, F: Fn(u64, u64) + Sync> trirhythm::monitor::Monitor<T> for Report<F> {
    fn progress(&self, done: u64, total: u64) {
        (self.0)(done, total)
    }
}

/// A progress bar on a terminal, hidden otherwise.
pub fn progress(len: u64, message: &str) -> indicatif::ProgressBar {
    use std::io::IsTerminal;
    if !std::io::stderr().is_terminal() {
        return indicatif::ProgressBar::hidden();
    }
    let bar = indicatif::ProgressBar::new(len);
    bar.set_style(
        indicatif::ProgressStyle::with_template("{msg} [{bar:40}] {pos}/{len} ({eta})")
            .expect("valid template")
            .progress_chars("=> "),
    );
    bar.set_message(message.to_string());
    bar
}

/// The library's [`trirhythm::monitor::Monitor`] drawn as a progress bar on the terminal (hidden otherwise).
pub struct Bar(indicatif::ProgressBar);

impl Bar {
    /// A bar labelled `message`, hidden until the first progress.
    pub fn new(message: &str) -> Bar {
        Bar(progress(0, message))
    }
}

impl<T: ?Sized> trirhythm::monitor::Monitor<T> for Bar {
    fn progress(&self, done: u64, total: u64) {
        self.0.set_length(total);
        self.0.set_position(done);
    }
}

impl Drop for Bar {
    fn drop(&mut self) {
        self.0.finish_and_clear();
    }
}
