//! One error type for the program: a one-line message and an exit code.

use std::fmt;

/// A failure of the program: `Usage` (exit 2: bad flags, bad scene, input outside the model's
/// domain) or `Solve` (exit 1: the solver did not converge, I/O failure, ...).
#[derive(Debug)]
pub enum Fail {
    /// bad input: exit code 2
    Usage(String),
    /// the computation or the output failed: exit code 1
    Solve(String),
    /// the reader of stdout went away (`vibrissa scan | head`): not an error of the program;
    /// exits quietly with code 0, as `rg`, `fd` and other Rust command-line tools do
    Closed,
}

impl Fail {
    /// Exit code of the process.
    pub fn code(&self) -> i32 {
        match self {
            Fail::Usage(_) => 2,
            Fail::Solve(_) => 1,
            Fail::Closed => 0,
        }
    }

    /// The message, flattened to one line.
    pub fn message(&self) -> String {
        let m = match self {
            Fail::Usage(m) | Fail::Solve(m) => m,
            Fail::Closed => "output closed by its reader",
        };
        // the model prints f64 with `{}`: 1e300 would be a 300-digit decimal
        crate::number_text::shorten_numbers(&one_line(m))
    }
}

impl fmt::Display for Fail {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message())
    }
}

/// Collapse whitespace runs (including newlines) to single spaces.
pub fn one_line(s: &str) -> String {
    s.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// Shorthand for a usage error.
pub fn usage(msg: impl Into<String>) -> Fail {
    Fail::Usage(msg.into())
}

/// Shorthand for a solve error.
pub fn solve_fail(msg: impl Into<String>) -> Fail {
    Fail::Solve(msg.into())
}

impl From<elastica::ElasticaError> for Fail {
    fn from(e: elastica::ElasticaError) -> Fail {
        if e.is_input() {
            Fail::Usage(e.to_string())
        } else {
            Fail::Solve(e.to_string())
        }
    }
}

/// The library's errors as the library classifies them: input (exit 2) or a failed solve.
impl From<vibrissa::VibrissaError> for Fail {
    fn from(e: vibrissa::VibrissaError) -> Fail {
        if e.is_input() {
            Fail::Usage(e.to_string())
        } else {
            Fail::Solve(e.to_string())
        }
    }
}

/// An output failure: [`Fail::Closed`] when its I/O cause is a broken pipe, else [`Fail::Solve`].
/// File outputs name themselves (`writing --out x.csv: ...`, see `output_files`); every other file
/// operation maps its error with its path, so an unnamed I/O error is a write to stdout.
fn output_fail(io_kind: Option<std::io::ErrorKind>, e: impl fmt::Display) -> Fail {
    if io_kind == Some(std::io::ErrorKind::BrokenPipe) {
        Fail::Closed
    } else {
        let m = e.to_string();
        if m.starts_with("writing ") || io_kind.is_none() {
            Fail::Solve(m)
        } else {
            Fail::Solve(format!("writing stdout: {m}"))
        }
    }
}

impl From<std::io::Error> for Fail {
    fn from(e: std::io::Error) -> Fail {
        output_fail(Some(e.kind()), e)
    }
}

impl From<csv::Error> for Fail {
    fn from(e: csv::Error) -> Fail {
        let kind = match e.kind() {
            csv::ErrorKind::Io(io) => Some(io.kind()),
            _ => None,
        };
        output_fail(kind, e)
    }
}

impl From<serde_json::Error> for Fail {
    fn from(e: serde_json::Error) -> Fail {
        output_fail(e.io_error_kind(), e)
    }
}

/// A hint in the user's terms for solver failures whose message is the model's own words (the
/// library's errors are mapped to [`Fail`] above; this adds what the user can do).
pub fn explain(f: Fail) -> Fail {
    let hint = |m: &str| -> Option<&'static str> {
        if m.contains("pulled at the tip (f < 0)") {
            Some("only a pulling force reaches this tip position, a surface cannot pull; in a scan the surface is then above the tip of the rod's rest shape: lower --eta or change the pre-curvature")
        } else if m.contains("homotopy from the uniform clamped rod failed") {
            Some("the start solve is followed from the paper's straight uniform rod to this scene and could not reach it; the scene may have no pushed contact at this height (try another --eta), or try another --method")
        } else {
            None
        }
    };
    match f {
        Fail::Solve(m) => match hint(&m) {
            Some(h) => Fail::Solve(format!("{m} ({h})")),
            None => Fail::Solve(m),
        },
        other => other,
    }
}

/// Library errors rendered with short numbers (the model prints `{}` of an `f64`).
pub fn shorten(f: Fail) -> Fail {
    match f {
        Fail::Usage(m) => Fail::Usage(crate::number_text::shorten_numbers(&m)),
        Fail::Solve(m) => Fail::Solve(crate::number_text::shorten_numbers(&m)),
        Fail::Closed => Fail::Closed,
    }
}

/// Result alias of the program.
pub type Res<T> = Result<T, Fail>;
