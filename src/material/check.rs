//! The value rules material extensions share, as messages naming the property (the caller
//! adds the file and the material).

/// `v` must be a finite number.
pub(super) fn finite(name: &str, v: f32) -> Result<(), String> {
    if v.is_finite() {
        Ok(())
    } else {
        Err(format!("{name} = {v} must be a finite number"))
    }
}

/// `v` must be a finite number in [0, 1].
pub(super) fn unit(name: &str, v: f32) -> Result<(), String> {
    finite(name, v)?;
    if (0.0..=1.0).contains(&v) {
        Ok(())
    } else {
        Err(format!("{name} = {v} must lie in [0, 1]"))
    }
}
