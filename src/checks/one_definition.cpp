// one_definition.cpp: a program that links every layer of the library whole (every object
// file, used or not). If two layers, or two files of one layer, define the same strong
// symbol (two functions `compare_texel_maps` with one signature, say), the link fails and
// so does the build: the one-definition rule, checked for the whole library.
int main() {
    return 0;
}
