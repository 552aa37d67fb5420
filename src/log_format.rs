//! How the log events of a run (`tracing::warn!` in the stages) print on stderr: in the
//! style of the scene's diagnostics, `FILE: warning: …` when the event carries a `file`
//! field, else `warning: …` (`error: …` for errors; other levels print the bare message).

use std::fmt::{self, Write as _};

use tracing::field::{Field, Visit};
use tracing::{Event, Level, Subscriber};
use tracing_subscriber::fmt::format::Writer;
use tracing_subscriber::fmt::{FmtContext, FormatEvent, FormatFields};
use tracing_subscriber::registry::LookupSpan;

/// The event format of the `stagelight` binary.
pub struct DiagnosticStyle;

/// The `message` and `file` fields of one event.
#[derive(Default)]
struct Fields {
    message: String,
    file: Option<String>,
}

impl Visit for Fields {
    fn record_debug(&mut self, field: &Field, value: &dyn fmt::Debug) {
        match field.name() {
            "message" => {
                let _ = write!(self.message, "{value:?}");
            }
            "file" => self.file = Some(format!("{value:?}")),
            _ => {}
        }
    }

    fn record_str(&mut self, field: &Field, value: &str) {
        match field.name() {
            "message" => self.message.push_str(value),
            "file" => self.file = Some(value.to_string()),
            _ => {}
        }
    }
}

/// The printed line of an event at `level` (without the newline).
fn line(level: Level, file: Option<&str>, message: &str) -> String {
    let severity = match level {
        Level::ERROR => "error: ",
        Level::WARN => "warning: ",
        _ => "",
    };
    match file {
        Some(f) => format!("{f}: {severity}{message}"),
        None => format!("{severity}{message}"),
    }
}

impl<S, N> FormatEvent<S, N> for DiagnosticStyle
where
    S: Subscriber + for<'a> LookupSpan<'a>,
    N: for<'a> FormatFields<'a> + 'static,
{
    fn format_event(
        &self,
        _ctx: &FmtContext<'_, S, N>,
        mut writer: Writer<'_>,
        event: &Event<'_>,
    ) -> fmt::Result {
        let mut fields = Fields::default();
        event.record(&mut fields);
        let level = *event.metadata().level();
        writeln!(
            writer,
            "{}",
            line(level, fields.file.as_deref(), &fields.message)
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn warnings_print_like_diagnostics() {
        assert_eq!(
            line(Level::WARN, Some("a.pmap"), "cannot reuse"),
            "a.pmap: warning: cannot reuse"
        );
        assert_eq!(line(Level::WARN, None, "dropped"), "warning: dropped");
        assert_eq!(line(Level::ERROR, None, "x"), "error: x");
        assert_eq!(line(Level::INFO, None, "x"), "x");
    }
}
