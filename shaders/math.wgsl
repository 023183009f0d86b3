#define_import_path filtered_ndf::math

const PI: f32 = 3.14159265358979;
