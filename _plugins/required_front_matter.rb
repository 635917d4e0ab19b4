# frozen_string_literal: true

# Every page in _pages/ must set `title:` (the heading, the browser tab and the sidebar
# check) and `permalink:` (its address; the navigation in _data/navigation.yml links to
# it). Say so by name, before Liquid reports an obscure undefined variable in the layout.
Jekyll::Hooks.register :site, :post_read do |site|
  missing = site.pages.filter_map do |page|
    next unless page.relative_path.start_with?("_pages/")

    keys = %w[title permalink].reject { |key| page.data[key].to_s.strip != "" }
    "#{page.relative_path}: #{keys.join(', ')}" unless keys.empty?
  end
  unless missing.empty?
    raise Jekyll::Errors::FatalException,
          "Pages without required front matter (title, permalink):\n  #{missing.join("\n  ")}"
  end
end
