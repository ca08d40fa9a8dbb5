//! Numbers and limits in words, for the metrics' messages.

use crate::geometry::{DriveLimit, LimitKind};

/// `x` to six decimals, without trailing zeros ("-30", "12.5"): numbers in messages.
pub(crate) fn short(x: f64) -> String {
    let text = format!("{x:.6}");
    let text = text.trim_end_matches('0').trim_end_matches('.');
    if text == "-0" {
        "0".to_owned()
    } else {
        text.to_owned()
    }
}

/// Why the drive stops at `limit`, in words.
pub(crate) fn reason(limit: &DriveLimit) -> String {
    let joints = limit.joints.join(", ");
    match limit.kind {
        LimitKind::Limit => {
            format!("a limit position: the loop of joints {joints} cannot close beyond it")
        }
        LimitKind::ChangePoint => {
            format!("a change point: the two branches of the loop of joints {joints} meet")
        }
        LimitKind::Toggle => format!("a toggle: the loop of joints {joints} is singular"),
        LimitKind::BranchFlip => {
            format!("beyond it the loop of joints {joints} would switch to its other branch")
        }
    }
}
