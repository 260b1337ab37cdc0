//! Exit codes and the error markers that select them.
//!
//! | code | meaning |
//! |---|---|
//! | 0 | success |
//! | 1 | the run failed: a solver failure, a non-converged solve, or an interrupt (Ctrl-C, SIGTERM) |
//! | 2 | bad input: an invalid scenario or case file, bad command-line arguments, an unusable `--out` |
//!
//! An error is bad input when its chain holds a [`BadInput`] marker (attached with
//! [`bad_input`] to everything that happens before the computation starts: reading and parsing
//! the file, building and validating the model, probing `--out`); every other error is a
//! failed run. clap exits with 2 on bad arguments by itself.

use std::fmt;

/// Exit code of a successful run.
pub const EXIT_OK: i32 = 0;
/// Exit code of a failed or interrupted run.
pub const EXIT_RUN_FAILED: i32 = 1;
/// Exit code of bad input (file, arguments, `--out`).
pub const EXIT_BAD_INPUT: i32 = 2;

/// Marker: the error is the user's input, not the computation.
#[derive(Debug)]
pub struct BadInput(String);

impl BadInput {
    /// A bad-input error with this message.
    pub fn error(message: impl Into<String>) -> anyhow::Error {
        anyhow::Error::new(BadInput(message.into()))
    }
}

impl fmt::Display for BadInput {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for BadInput {}

/// Mark an error (from parsing or validating input) as bad input, keeping its message.
pub fn bad_input(e: anyhow::Error) -> anyhow::Error {
    if is_bad_input(&e) {
        e
    } else {
        BadInput::error(error_text(&e))
    }
}

/// The error's message with its causes, `outer: cause: …`, each text once.
///
/// The libraries' errors often repeat their cause in their own message ("bridge: {0}" over
/// a `#[from]` source, so that a plain `{e}` is complete); anyhow's `{e:#}` would then print
/// the cause twice. A cause whose text the message so far already ends with is skipped.
pub fn error_text(e: &anyhow::Error) -> String {
    let mut text = String::new();
    for cause in e.chain() {
        let part = cause.to_string();
        if text.is_empty() {
            text = part;
        } else if !text.ends_with(&part) {
            text.push_str(": ");
            text.push_str(&part);
        }
    }
    text
}

fn is_bad_input(e: &anyhow::Error) -> bool {
    e.chain().any(|c| c.is::<BadInput>())
}

/// The process exit code for an error.
pub fn exit_code(e: &anyhow::Error) -> i32 {
    if is_bad_input(e) {
        EXIT_BAD_INPUT
    } else {
        EXIT_RUN_FAILED
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use anyhow::Context;

    #[test]
    fn classification_survives_context() {
        let e = Err::<(), _>(BadInput::error("[bridge] length = -1"))
            .context("reading x.toml")
            .unwrap_err();
        assert_eq!(exit_code(&e), EXIT_BAD_INPUT);
        assert_eq!(format!("{e:#}"), "reading x.toml: [bridge] length = -1");
        let run = anyhow::anyhow!("step 3 of 10: Newton did not converge");
        assert_eq!(exit_code(&run), EXIT_RUN_FAILED);
        assert_eq!(exit_code(&bad_input(run)), EXIT_BAD_INPUT);
    }

    #[derive(Debug, thiserror::Error)]
    #[error("singular matrix")]
    struct Inner;

    #[derive(Debug, thiserror::Error)]
    enum Outer {
        #[error("bridge: {0}")]
        Prefixed(#[from] Inner),
        #[error("{0}")]
        Plain(#[source] Inner),
        #[error("wheel 3")]
        Bare(#[source] Inner),
    }

    #[test]
    fn error_text_prints_each_cause_once() {
        let prefixed = anyhow::Error::from(Outer::Prefixed(Inner)).context("running x.toml");
        assert_eq!(
            format!("{prefixed:#}"),
            "running x.toml: bridge: singular matrix: singular matrix"
        );
        assert_eq!(
            error_text(&prefixed),
            "running x.toml: bridge: singular matrix"
        );
        let plain = anyhow::Error::from(Outer::Plain(Inner));
        assert_eq!(error_text(&plain), "singular matrix");
        let bare = anyhow::Error::from(Outer::Bare(Inner));
        assert_eq!(error_text(&bare), "wheel 3: singular matrix");
        assert_eq!(exit_code(&bad_input(prefixed)), EXIT_BAD_INPUT);
    }
}
