//! Progress of long work (bench runs, calibrations, references, videos) that people can
//! read: on a terminal a bar with the time left; elsewhere (a CI log, a pipe) a plain line
//! on stderr at every few percent, where indicatif alone would show nothing.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle, TermLike};
use std::io::IsTerminal;
use std::sync::atomic::{AtomicU64, Ordering};

/// Percent between two plain lines when stderr is not a terminal.
const PLAIN_STEP_PERCENT: u64 = 5;

/// A bar over `len` units named `unit` (e.g. "frames"), with the message after it.
pub fn progress_bar(len: u64, unit: &str) -> ProgressBar {
    let progress = ProgressBar::new(len);
    let tail = format!("{{pos}}/{{len}} {unit}, {{msg}} [{{elapsed}}, about {{eta}} left]");
    let template = if std::io::stderr().is_terminal() {
        format!("{{bar:40}} {tail}")
    } else {
        progress.set_draw_target(ProgressDrawTarget::term_like_with_hz(
            Box::new(PlainLines::default()),
            4,
        ));
        format!("{{percent}}% {tail}")
    };
    progress.set_style(
        ProgressStyle::with_template(&template).expect("the progress template is valid"),
    );
    progress
}

/// A draw target that writes a drawn line to stderr only when its leading percentage
/// reaches the next multiple of [`PLAIN_STEP_PERCENT`].
#[derive(Debug)]
struct PlainLines {
    last_step: AtomicU64,
}

impl Default for PlainLines {
    fn default() -> Self {
        Self {
            last_step: AtomicU64::new(u64::MAX),
        }
    }
}

impl PlainLines {
    fn show(&self, line: &str) {
        let Some(percent) = line
            .split('%')
            .next()
            .and_then(|p| p.trim().parse::<u64>().ok())
        else {
            return;
        };
        let step = percent / PLAIN_STEP_PERCENT;
        if self.last_step.swap(step, Ordering::Relaxed) != step {
            eprintln!("{}", line.trim_end());
        }
    }
}

impl TermLike for PlainLines {
    fn width(&self) -> u16 {
        200
    }
    fn move_cursor_up(&self, _n: usize) -> std::io::Result<()> {
        Ok(())
    }
    fn move_cursor_down(&self, _n: usize) -> std::io::Result<()> {
        Ok(())
    }
    fn move_cursor_right(&self, _n: usize) -> std::io::Result<()> {
        Ok(())
    }
    fn move_cursor_left(&self, _n: usize) -> std::io::Result<()> {
        Ok(())
    }
    fn write_line(&self, s: &str) -> std::io::Result<()> {
        self.show(s);
        Ok(())
    }
    fn write_str(&self, s: &str) -> std::io::Result<()> {
        self.show(s);
        Ok(())
    }
    fn clear_line(&self) -> std::io::Result<()> {
        Ok(())
    }
    fn flush(&self) -> std::io::Result<()> {
        Ok(())
    }
}
