//! What the records hold, as read back: a unit's certificates, a centrifuge's campaigns and
//! balance events. Plain values; the history is computed from them.

use crate::date::Date;
use crate::submission::UnitIdentity;

/// One certified coefficient of a stored certificate.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct StoredTerm {
    /// `k0` … `k3`.
    pub term: String,
    /// `ia_in`, `ia_out`; absent when the mountings share it.
    pub mounting: Option<String>,
    /// Its unit (`rad/(s·g²)`).
    pub unit: String,
    /// The value certified.
    pub value: f64,
    /// Its standard uncertainty.
    pub u: f64,
    /// Its expanded uncertainty (95 %).
    pub expanded: f64,
}

impl StoredTerm {
    /// `k2`, or `k0 (ia_out)` for a coefficient of one mounting.
    pub fn label(&self) -> String {
        match &self.mounting {
            Some(m) => format!("{} ({m})", self.term),
            None => self.term.clone(),
        }
    }
}

/// A stored certificate.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct StoredCertificate {
    /// Its identification.
    pub id: String,
    /// The first day of the measurement (the date its values hold at).
    pub measured: Date,
    /// The date of issue.
    pub issued: Date,
    /// `probe` or `two_orientation`.
    pub method: String,
    /// The record (SHA-256 of its results.json).
    pub record: String,
    /// The certificate it supersedes (corrects), if any.
    pub supersedes: Option<String>,
    /// The certificate that supersedes it, if any: then it is not current.
    pub superseded_by: Option<String>,
    /// SHA-256 of its DCC, when recorded.
    pub dcc_sha256: Option<String>,
    /// SHA-256 of its PDF, when recorded.
    pub pdf_sha256: Option<String>,
    /// The coefficients certified, in the certificate's order.
    pub terms: Vec<StoredTerm>,
    /// Their covariance, in that order.
    pub covariance: Vec<Vec<f64>>,
}

impl StoredCertificate {
    /// Whether no other certificate supersedes it.
    pub fn is_current(&self) -> bool {
        self.superseded_by.is_none()
    }
}

/// A unit's records.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct UnitRecords {
    /// The unit.
    pub unit: UnitIdentity,
    /// Its certificates by date of measurement, superseded ones included.
    pub certificates: Vec<StoredCertificate>,
}

/// One campaign's probe phase on a centrifuge.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Campaign {
    /// The date of measurement.
    pub date: Date,
    /// The study's name.
    pub study: String,
    /// The probe phase: the one the calibration compensated with, else the study's last.
    pub phase: String,
    /// C_r, m·s².
    pub c_r_m_s2: f64,
    /// Its standard uncertainty, when the study gives one.
    pub c_r_u_m_s2: Option<f64>,
    /// The radius error's constant term, µm.
    pub offset_um: f64,
    /// Δk2 = k1·C_r·g/R², rad/(s·g²).
    pub delta_k2_rad_s_g2: f64,
    /// Its standard uncertainty, when the study gives one.
    pub delta_k2_u_rad_s_g2: Option<f64>,
}

/// A balancing of the centrifuge.
#[derive(Debug, Clone, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct BalanceEvent {
    /// Its date.
    pub date: Date,
    /// What was done, in the lab's words.
    pub note: String,
}

/// A centrifuge's records.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct CentrifugeRecords {
    /// Its name.
    pub name: String,
    /// Its campaigns by date.
    pub campaigns: Vec<Campaign>,
    /// Its balance events by date.
    pub balances: Vec<BalanceEvent>,
}
