// Shadow maps write depth only.
void main() {}
