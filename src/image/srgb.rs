//! The sRGB transfer functions (IEC 61966-2-1:1999, §5.2) between linear values and
//! sRGB-encoded values, both in [0, 1]:
//! - OETF (encode): `V = 12.92 L` for `L ≤ 0.0031308`, else `V = 1.055 L^(1/2.4) − 0.055`;
//! - EOTF (decode): `L = V / 12.92` for `V ≤ 0.04045`, else `L = ((V + 0.055) / 1.055)^2.4`.
//!
//! 8-bit output encodes with the OETF ([`crate::output::tonemap`]); 8-bit textures and
//! `--background` colours decode with the EOTF.

/// The sRGB opto-electronic transfer function (IEC 61966-2-1), input clamped to [0, 1].
pub fn srgb_oetf(l: f32) -> f32 {
    let l = if l.is_nan() { 0.0 } else { l.clamp(0.0, 1.0) };
    if l <= 0.003_130_8 {
        12.92 * l
    } else {
        1.055 * l.powf(1.0 / 2.4) - 0.055
    }
}

/// The sRGB electro-optical transfer function (IEC 61966-2-1 §5.2): an encoded value in
/// [0, 1] to linear, the inverse of [`srgb_oetf`]. Textures and `--background` colours
/// decode with it.
pub fn srgb_eotf(v: f32) -> f32 {
    if v <= 0.040_45 {
        v / 12.92
    } else {
        ((v + 0.055) / 1.055).powf(2.4)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn eotf_inverts_oetf_on_both_branches() {
        for i in 0..=1000 {
            let l = i as f32 / 1000.0;
            let back = srgb_eotf(srgb_oetf(l));
            assert!((back - l).abs() < 1e-5 * l.max(1e-2), "{l} -> {back}");
        }
        assert_eq!(srgb_eotf(0.0), 0.0);
        assert!((srgb_eotf(1.0) - 1.0).abs() < 1e-6);
    }
}
