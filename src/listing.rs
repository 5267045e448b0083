//! What `srt scenes` and `srt info` print: rows of a name and a value, the values aligned, on
//! standard output. A reader that goes away (`srt info x.png | head -1`) ends the listing
//! quietly, as other command-line tools do ([`ends_quietly`]).

use std::io::Write as _;

/// Prints `rows` as `name  value` lines, the values in one column.
///
/// # Errors
/// Writing to standard output failed (a closed pipe among them: see [`ends_quietly`]).
pub fn print_rows<'a>(rows: impl IntoIterator<Item = (&'a str, &'a str)>) -> std::io::Result<()> {
    let rows: Vec<(&str, &str)> = rows.into_iter().collect();
    let width = rows
        .iter()
        .map(|(name, _)| name.chars().count())
        .max()
        .unwrap_or(0);
    let mut out = std::io::stdout().lock();
    for (name, value) in rows {
        writeln!(out, "{name:width$}  {value}")?;
    }
    out.flush()
}

/// `result`, except that standard output closed by its reader (a broken pipe) is success: the
/// reader has what it wanted.
pub fn ends_quietly(result: anyhow::Result<()>) -> anyhow::Result<()> {
    match result {
        Err(error)
            if error
                .downcast_ref::<std::io::Error>()
                .is_some_and(|io| io.kind() == std::io::ErrorKind::BrokenPipe) =>
        {
            Ok(())
        }
        other => other,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_closed_pipe_is_success_and_other_errors_stay() {
        let pipe = std::io::Error::from(std::io::ErrorKind::BrokenPipe);
        assert!(ends_quietly(Err(pipe.into())).is_ok());
        let denied = std::io::Error::from(std::io::ErrorKind::PermissionDenied);
        assert!(ends_quietly(Err(denied.into())).is_err());
        assert!(ends_quietly(Err(anyhow::anyhow!("no such scene"))).is_err());
    }
}
