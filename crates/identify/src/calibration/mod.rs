//! Centrifuge calibration of a PIGA (eq. 17–18) and its compensation for the spindle's dynamic
//! radius error (eq. 19). Read `fit` (the design and the fit), then `compensated`.

mod compensated;
mod fit;
#[cfg(test)]
mod tests;

pub use compensated::{
    CompensatedCalibration, Compensation, K1Source, identify_compensated,
    identify_compensated_weighted,
};
pub use fit::{
    CALIBRATION_TERMS, Calibration, MIN_DISTINCT_RATES, calibration_design, calibration_row,
    identify_calibration, identify_calibration_weighted,
};
