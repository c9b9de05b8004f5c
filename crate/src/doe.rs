//! Placeholder: Audze-Eglais and factorial sampling plans (being written).
