layout(local_size_x = 1) in;
void main() {
  this_is_not_glsl;
}
