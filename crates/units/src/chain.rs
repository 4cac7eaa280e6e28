//! How an error and its causes become one line of text.

use std::error::Error;
use std::fmt;

/// An error and its causes joined by `: `, leaving out a cause whose text the line already
/// holds (the libraries' messages often include their source's): the one way the command
/// line, the study's list of problems and Python write an error chain.
///
/// ```
/// #[derive(Debug)]
/// struct Inner;
/// impl std::fmt::Display for Inner {
///     fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result { f.write_str("disk full") }
/// }
/// impl std::error::Error for Inner {}
/// #[derive(Debug)]
/// struct Outer(Inner, &'static str);
/// impl std::fmt::Display for Outer {
///     fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result { f.write_str(self.1) }
/// }
/// impl std::error::Error for Outer {
///     fn source(&self) -> Option<&(dyn std::error::Error + 'static)> { Some(&self.0) }
/// }
/// assert_eq!(units::ErrorChain(&Outer(Inner, "cannot write out.csv")).to_string(),
///            "cannot write out.csv: disk full");
/// // a cause already said is not said twice
/// assert_eq!(units::ErrorChain(&Outer(Inner, "cannot write out.csv (disk full)")).to_string(),
///            "cannot write out.csv (disk full)");
/// ```
#[derive(Clone, Copy)]
pub struct ErrorChain<'a>(pub &'a (dyn Error + 'static));

impl fmt::Display for ErrorChain<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut out = String::new();
        let mut next: Option<&(dyn Error + 'static)> = Some(self.0);
        while let Some(cause) = next {
            let text = cause.to_string();
            if !out.contains(&text) {
                if !out.is_empty() {
                    out.push_str(": ");
                }
                out.push_str(&text);
            }
            next = cause.source();
        }
        f.write_str(&out)
    }
}

impl fmt::Debug for ErrorChain<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Display::fmt(self, f)
    }
}
