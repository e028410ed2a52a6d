//! Standard output that reports write errors, and JSON as the commands print it.

pub(crate) fn is_broken_pipe(e: &(dyn std::error::Error + 'static)) -> bool {
    e.downcast_ref::<std::io::Error>()
        .is_some_and(|e| e.kind() == std::io::ErrorKind::BrokenPipe)
}

/// Writes `text` to standard output and flushes, returning write errors (a closed pipe, a
/// full disk) instead of panicking as `print!` does.
pub(crate) fn out(text: &str) -> Result<(), Box<dyn std::error::Error>> {
    use std::io::Write;
    let mut stdout = std::io::stdout().lock();
    stdout
        .write_all(text.as_bytes())
        .and_then(|()| stdout.flush())
        .map_err(|e| {
            if e.kind() == std::io::ErrorKind::BrokenPipe {
                e.into()
            } else {
                format!("cannot write to standard output: {e}").into()
            }
        })
}

/// [`out`] for a run that was interrupted: a reader that went away is not an error and
/// does not hide the interruption (the exit code stays 130).
pub(crate) fn out_interrupted(text: &str) -> Result<(), Box<dyn std::error::Error>> {
    match out(text) {
        Err(e) if is_broken_pipe(e.as_ref()) => Ok(()),
        done => done,
    }
}

/// Pretty JSON with a final newline.
pub(crate) fn json(value: &impl serde::Serialize) -> Result<String, Box<dyn std::error::Error>> {
    Ok(serde_json::to_string_pretty(value)? + "\n")
}
