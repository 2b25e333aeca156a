//! Which Box2D this binary links: its precision, its SIMD path and the C
//! flags it was compiled with, read from the build (cargo features and the
//! environment `cargo` gave the compile) and, for the SIMD path, from the
//! CPU at run time. The benchmark names its Box2D rows from this and
//! prints it, instead of fixed text.
//!
//! - Precision: boxdd's `double-precision` feature (this crate's
//!   `box2d-double`) makes Box2D's absolute positions f64 (`b2Pos`); its
//!   velocities, rotations, masses and impulses stay f32. Without it every
//!   value is f32.
//! - SIMD: boxdd's `simd-avx2` feature (this crate's `box2d-avx2`) defines
//!   `BOX2D_AVX2` and compiles every Box2D source with `-mavx2`: its
//!   contact solver then works on 8 f32 lanes, and the compiler may use
//!   AVX2 anywhere in Box2D. Without it Box2D takes its SSE2 path (4 f32
//!   lanes), which every x86-64 CPU has. The AVX2 build cannot run on a
//!   CPU without AVX2 (the first such instruction stops the process with
//!   SIGILL), so [`Box2dBuild::runnable`] checks the CPU before any Box2D
//!   call.
//! - C flags: boxdd-sys's build script compiles Box2D through the `cc`
//!   crate at `-O2` (release) with `-std=c17 -ffp-contract=off`, without
//!   `NDEBUG`; `cc` then appends `CFLAGS_<target>` from the environment,
//!   which the workspace's `.cargo/config.toml` sets to `-O3 -DNDEBUG`
//!   (Box2D's release configuration). The same variable is read here at
//!   compile time (cargo gives its `[env]` table to every compile), so
//!   what is printed is what the build script received.

/// The C flags `cc` appended to boxdd-sys's own for this target (empty if
/// none were set).
const TARGET_CFLAGS: &str = match option_env!("CFLAGS_x86_64_unknown_linux_gnu") {
    Some(flags) => flags,
    None => "",
};

/// A description of the linked Box2D build.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Box2dBuild {
    /// "f32", or "f64 positions" for the large-world build.
    pub precision: &'static str,
    /// The SIMD path compiled in: "AVX2" or "SSE2" (or "scalar" on other
    /// architectures).
    pub simd: &'static str,
    /// Lanes of the contact solver's wide floats.
    pub lanes: usize,
    /// Optimisation level in effect (the last `-O` given).
    pub optimisation: String,
    /// Whether `NDEBUG` is defined (Box2D's assertions compiled out).
    pub ndebug: bool,
    /// The full flags: boxdd-sys's, then the environment's.
    pub flags: String,
}

impl Box2dBuild {
    /// The build linked into this binary.
    pub fn linked() -> Self {
        let avx2 = cfg!(all(feature = "box2d-avx2", target_arch = "x86_64"));
        let (simd, lanes) = if avx2 {
            ("AVX2", 8)
        } else if cfg!(target_arch = "x86_64") {
            ("SSE2", 4)
        } else {
            ("scalar", 1)
        };
        let extra: Vec<&str> = TARGET_CFLAGS.split_whitespace().collect();
        let optimisation = extra
            .iter()
            .rev()
            .find(|f| f.starts_with("-O"))
            .map_or("-O2".to_string(), |f| f.to_string());
        let ndebug = extra.contains(&"-DNDEBUG");
        let mut flags = String::from("-O2 -std=c17 -ffp-contract=off");
        if avx2 {
            flags += " -DBOX2D_AVX2 -mavx2";
        }
        if cfg!(feature = "box2d-double") {
            flags += " -DBOX2D_DOUBLE_PRECISION";
        }
        if !extra.is_empty() {
            flags += " then ";
            flags += &extra.join(" ");
        }
        Self {
            precision: if cfg!(feature = "box2d-double") {
                "f64 positions"
            } else {
                "f32"
            },
            simd,
            lanes,
            optimisation,
            ndebug,
            flags,
        }
    }

    /// The benchmark's name for this build, e.g. "Box2D 3.2 f32 AVX2 -O3
    /// NDEBUG".
    pub fn bench_name(&self) -> String {
        format!(
            "Box2D 3.2 {} {} {}{}",
            if self.precision == "f32" {
                "f32"
            } else {
                "f64-pos"
            },
            self.simd,
            self.optimisation,
            if self.ndebug { " NDEBUG" } else { " asserts" }
        )
    }

    /// Whether this CPU can run the build: `Err` with the reason when the
    /// build uses AVX2 and the CPU lacks it (checked before any Box2D call,
    /// as the first AVX2 instruction would stop the process).
    pub fn runnable(&self) -> Result<(), String> {
        #[cfg(target_arch = "x86_64")]
        if self.simd == "AVX2" && !std::is_x86_feature_detected!("avx2") {
            return Err(
                "this Box2D build uses AVX2 (boxdd's simd-avx2 feature) and this CPU \
                 has no AVX2; build without the `box2d-avx2` feature (or run `harness \
                 bench --box2d-sse2`) to run Box2D here"
                    .into(),
            );
        }
        Ok(())
    }

    /// The SIMD path Box2D takes on this CPU: its compiled path if the CPU
    /// has it, else "none (CPU lacks AVX2)".
    pub fn simd_at_run_time(&self) -> String {
        match self.runnable() {
            Ok(()) => format!("{} ({} f32 lanes)", self.simd, self.lanes),
            Err(_) => format!("none: compiled for {}, which this CPU lacks", self.simd),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_name_says_the_compiled_simd_path_and_flags() {
        let b = Box2dBuild::linked();
        let name = b.bench_name();
        assert!(name.contains(b.simd), "{name}");
        assert!(name.contains(&b.optimisation), "{name}");
        assert_eq!(
            b.simd == "AVX2",
            cfg!(all(feature = "box2d-avx2", target_arch = "x86_64"))
        );
        // The workspace's .cargo/config.toml asks for Box2D's release flags.
        assert_eq!(TARGET_CFLAGS, "-O3 -DNDEBUG");
        assert_eq!(b.optimisation, "-O3");
        assert!(b.ndebug);
    }
}
