// Depth only: nothing to write.
void main() {}
