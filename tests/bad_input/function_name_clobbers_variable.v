/* Its names become preprocessor macros for the .l file, as in cpfg. */
function set: widths.fset
