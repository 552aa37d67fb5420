//! An instance `transform`'s 16 numbers as the affine matrix the rest of the reader takes.
//!
//! mental ray writes the matrix row by row for row vectors (`p_object = p_world · M`), so an
//! affine one has the translation in its last row and `(0, 0, 0, 1)` as its last column.
//! Exporters also print it homogeneous, scaled by some `w` (seed 001 §3.2.2 ends its sphere
//! transform with `0 0 2.0 0.2`): the last column `(0, 0, 0, w)` with `w ≠ 0` is the same
//! transform, read divided by `w`. A last column of any other shape is projective and
//! cannot place an instance: a located error in the terms the file wrote it.

use super::super::located::{Pos, Problem};

/// The affine matrix of the 16 numbers `m` (row by row, each written at `at`), `w`
/// divided out; else the error describing the last column as written, at its first
/// number out of place.
pub fn affine(m: &[f64; 16], at: &[Pos; 16]) -> Result<[f64; 16], Problem> {
    let column = [m[3], m[7], m[11], m[15]];
    let w = column[3];
    let homogeneous = column[..3].iter().all(|&x| x == 0.0) && w.is_finite() && w != 0.0;
    if !homogeneous {
        let wrong = (0..3).find(|&k| column[k] != 0.0).unwrap_or(3);
        let at = at[4 * wrong + 3];
        let shown: Vec<String> = column.iter().map(|x| format!("{x}")).collect();
        return Err(Problem::error(
            at,
            format!(
                "the last column of a transform must be (0, 0, 0, w) with w ≠ 0, found ({})",
                shown.join(", ")
            ),
        )
        .with_help(
            "an instance transform is affine, written row by row with the translation in the \
             last row: its last column is (0, 0, 0, 1), or (0, 0, 0, w) for a matrix scaled by w",
        ));
    }
    let mut a = m.map(|x| x / w);
    a[15] = 1.0;
    Ok(a)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The numbers written one a column on line 3.
    const AT: [Pos; 16] = {
        let mut at = [Pos { line: 3, column: 1 }; 16];
        let mut k = 0;
        while k < 16 {
            at[k].column = 1 + 2 * k;
            k += 1;
        }
        at
    };

    /// Seed 001 §3.2.2's sphere transform: scale 0.2 and translation (0, 0, 2), scaled by
    /// 0.2 — the identity scale and a translation of 10.
    #[test]
    fn a_homogeneous_matrix_is_divided_by_its_w() {
        let m = [
            0.2, 0.0, 0.0, 0.0, 0.0, 0.2, 0.0, 0.0, 0.0, 0.0, 0.2, 0.0, 0.0, 0.0, 2.0, 0.2,
        ];
        let a = affine(&m, &AT).unwrap();
        assert_eq!(
            a,
            [1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 10.0, 1.0]
        );
    }

    #[test]
    fn a_projective_matrix_or_w_zero_is_refused_as_written() {
        let mut m = [0.0; 16];
        (m[0], m[5], m[10], m[11], m[15]) = (1.0, 1.0, 1.0, -1.0, 1.0);
        let e = affine(&m, &AT).unwrap_err();
        assert_eq!(
            e.message,
            "the last column of a transform must be (0, 0, 0, w) with w ≠ 0, found (0, 0, -1, 1)"
        );
        // At the number out of place: the third row's last.
        assert_eq!(e.pos, AT[11]);
        m[11] = 0.0;
        m[15] = 0.0;
        let e = affine(&m, &AT).unwrap_err();
        assert!(e.message.ends_with("found (0, 0, 0, 0)"));
        assert_eq!(e.pos, AT[15]);
    }
}
