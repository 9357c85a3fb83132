//! The scan by the closed forms (paper's scene only).

use crate::report::{ScanOptions, ScanResult};
use crate::{Model, VibrissaError};

pub(crate) fn scan_analytic(
    model: &Model,
    _opts: &ScanOptions,
    _grid: &[f64],
) -> Result<ScanResult, VibrissaError> {
    if !model.is_paper_scene() {
        return Err(VibrissaError::MethodUnavailable {
            method: "analytic".into(),
            reason: "closed forms exist only for the paper's scene (uniform, straight, clamped rod, horizontal surface)".into(),
        });
    }
    Err(VibrissaError::MethodUnavailable {
        method: "analytic".into(),
        reason: "the closed-form scan is elastica::ClosedFormScan (parametrised by alpha and phi1, not d); vibrissa::scan needs a numerical method".into(),
    })
}
