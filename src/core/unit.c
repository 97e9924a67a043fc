/* An empty translation unit so that a concept library with no sources yet still builds. */
typedef int us_unit_placeholder;
