/* An environment map whose file is an OpenEXR header cut short. */
trace environment: trace_environment_broken.exr
