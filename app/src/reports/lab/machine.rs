//! The machine a report was measured on: CPU, cores, OS, the workbench's
//! version and commit, and the date, so two reports can be compared.

use web_time::{SystemTime, UNIX_EPOCH};

/// What a reader needs to compare two reports' times.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Machine {
    /// The CPU's model name (`/proc/cpuinfo`), or the architecture.
    pub(crate) cpu: String,
    /// Logical CPUs this process may use.
    pub(crate) cpus: usize,
    /// The OS's name and version, and the kernel's.
    pub(crate) os: String,
    pub(crate) version: &'static str,
    /// The git commit the binary was built from ("unknown" outside git).
    pub(crate) commit: &'static str,
    /// When the report was measured, UTC (`YYYY-MM-DD HH:MM UTC`).
    pub(crate) date: String,
}

impl Machine {
    /// This machine, now.
    pub(crate) fn this() -> Machine {
        let cpuinfo = std::fs::read_to_string("/proc/cpuinfo").unwrap_or_default();
        let os_release = std::fs::read_to_string("/etc/os-release").unwrap_or_default();
        let kernel = std::fs::read_to_string("/proc/sys/kernel/osrelease").unwrap_or_default();
        let os = match os_name(&os_release) {
            Some(name) if !kernel.trim().is_empty() => format!("{name}, kernel {}", kernel.trim()),
            Some(name) => name,
            None => std::env::consts::OS.to_string(),
        };
        Machine {
            cpu: cpu_model(&cpuinfo).unwrap_or_else(|| std::env::consts::ARCH.to_string()),
            cpus: std::thread::available_parallelism().map_or(1, |n| n.get()),
            os,
            version: env!("CARGO_PKG_VERSION"),
            commit: env!("WORKBENCH_COMMIT"),
            date: utc_date(SystemTime::now()),
        }
    }
}

/// The first `model name` of a `/proc/cpuinfo` text.
fn cpu_model(cpuinfo: &str) -> Option<String> {
    cpuinfo.lines().find_map(|line| {
        let (key, value) = line.split_once(':')?;
        (key.trim() == "model name" && !value.trim().is_empty()).then(|| value.trim().to_string())
    })
}

/// `PRETTY_NAME` of an `/etc/os-release` text, unquoted.
fn os_name(os_release: &str) -> Option<String> {
    os_release.lines().find_map(|line| {
        let value = line.strip_prefix("PRETTY_NAME=")?;
        Some(value.trim().trim_matches('"').to_string())
    })
}

/// `time` as `YYYY-MM-DD HH:MM UTC` (the proleptic Gregorian calendar,
/// from days since 1970 as in Howard Hinnant's `civil_from_days`).
pub(crate) fn utc_date(time: SystemTime) -> String {
    let secs = time.duration_since(UNIX_EPOCH).map_or(0, |d| d.as_secs());
    let (days, rest) = ((secs / 86_400) as i64, secs % 86_400);
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    let year = yoe + era * 400 + i64::from(month <= 2);
    format!(
        "{year:04}-{month:02}-{day:02} {:02}:{:02} UTC",
        rest / 3600,
        rest % 3600 / 60
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::Duration;

    #[test]
    fn dates_are_gregorian() {
        let at = |secs| utc_date(UNIX_EPOCH + Duration::from_secs(secs));
        assert_eq!(at(0), "1970-01-01 00:00 UTC");
        // 2000-02-29 12:34, a leap day in a century leap year.
        assert_eq!(at(951_827_640), "2000-02-29 12:34 UTC");
        assert_eq!(at(1_767_225_599), "2025-12-31 23:59 UTC");
    }

    #[test]
    fn cpu_and_os_names_are_read() {
        let cpuinfo = "processor\t: 0\nmodel name\t: Example CPU @ 3.0GHz\nflags\t: x\n";
        assert_eq!(cpu_model(cpuinfo).as_deref(), Some("Example CPU @ 3.0GHz"));
        assert_eq!(cpu_model("processor : 0\n"), None);
        let release = "NAME=\"Debian\"\nPRETTY_NAME=\"Debian GNU/Linux 13\"\n";
        assert_eq!(os_name(release).as_deref(), Some("Debian GNU/Linux 13"));
    }
}
